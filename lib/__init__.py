"""rfc.lib: the hardware library that generated systems are built from."""
