"""Message types, their flattened layouts, selections and the reference codec."""
