"""Blocks that connect Vitis HLS cores to rfc's message handshakes."""
