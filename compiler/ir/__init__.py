"""The IR: a typed data-flow graph with source locations, its text form and its invariants."""
