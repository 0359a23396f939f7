"""rfc.runtime: what runs on the processor side of a generated system."""
