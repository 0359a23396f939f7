"""Configured maxima, re-exported: they live in `rfc.runtime.limits` (the runtime checks them)."""

from __future__ import annotations

from rfc.runtime.limits import MAX_LENGTH, Limits

__all__ = ["MAX_LENGTH", "Limits"]
