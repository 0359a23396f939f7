"""The image stages in NumPy, and as references on rosbags sensor_msgs/Image messages.

`gray`, `downscale` and `integral` are the formulas of the three stages on arrays: the oracle
the hardware is held to, pixel for pixel. The ``*_reference`` functions apply them to rosbags
messages, keeping the header, as the spec's ``reference:`` entries and the ROS-SW fallback.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from rfc.messages.rosbags_adapter import message_types

IMAGE = "sensor_msgs/msg/Image"


def gray(rgb: np.ndarray) -> np.ndarray:
    """rgb8 (height by width by 3) to mono8: OpenCV's integer BT.601 luma."""
    r, g, b = (rgb[..., i].astype(np.int64) for i in range(3))
    return ((4899 * r + 9617 * g + 1868 * b + 8192) >> 14).astype(np.uint8)


def downscale(image: np.ndarray) -> np.ndarray:
    """Half width and height (floor): the rounded mean of each 2x2 block."""
    h, w = image.shape[0] // 2 * 2, image.shape[1] // 2 * 2
    blocks = image[:h, :w].astype(np.int64).reshape(h // 2, 2, w // 2, 2)
    return ((blocks.sum(axis=(1, 3)) + 2) >> 2).astype(np.uint8)


def integral(image: np.ndarray) -> np.ndarray:
    """Each pixel the sum of the image over the rows and columns up to it, as uint32."""
    return image.astype(np.uint32).cumsum(axis=0).cumsum(axis=1).astype("<u4")


def pipeline(rgb: np.ndarray) -> np.ndarray:
    """The three stages one after the other."""
    return integral(downscale(gray(rgb)))


def pixels(message: Any, channels: int, dtype: str = "u1") -> np.ndarray:
    """A message's data as a height by width (by channels) array."""
    shape = (message.height, message.width) + ((channels,) if channels > 1 else ())
    return np.frombuffer(bytes(message.data), dtype=dtype).reshape(shape)


def image_message(like: Any, image: np.ndarray, encoding: str) -> Any:
    """A sensor_msgs/Image of `image` with the header of message `like`."""
    types = message_types("ros2")
    data = np.ascontiguousarray(image)
    height, width = data.shape[:2]
    header = {
        "stamp": {"sec": like.header.stamp.sec, "nanosec": like.header.stamp.nanosec},
        "frame_id": like.header.frame_id,
    }
    fields = {
        "header": header,
        "height": height,
        "width": width,
        "encoding": encoding,
        "is_bigendian": 0,
        "step": data.itemsize * width * (data.shape[2] if data.ndim > 2 else 1),
        "data": np.frombuffer(data.tobytes(), dtype=np.uint8),
    }
    return types.build(IMAGE, fields)


def rgb_to_gray_reference(rgb: Any) -> Any:
    """RgbToGray on a rosbags image."""
    return image_message(rgb, gray(pixels(rgb, 3)), "mono8")


def downscale_reference(full: Any) -> Any:
    """Downscale on a rosbags image."""
    return image_message(full, downscale(pixels(full, 1)), "mono8")


def integral_image_reference(image: Any) -> Any:
    """IntegralImage on a rosbags image."""
    return image_message(image, integral(pixels(image, 1)), "32SC1")
