"""Hardware message converters: subscriber, publisher and frame-length circuit (paper §4.2)."""
