"""Vectoring CORDIC (atan2 and magnitude): configuration, bit-exact model, MyHDL blocks."""

from rfc.lib.cordic.config import CordicConfig
from rfc.lib.cordic.model import Vectored, vectoring

__all__ = ["CordicConfig", "Vectored", "vectoring"]
