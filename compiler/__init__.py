"""rfc: from a compact robotics system description to an FPGA hardware/software architecture."""

__version__ = "0.1.0"
