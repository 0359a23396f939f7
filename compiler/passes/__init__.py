"""The pass pipeline: named steps from the parsed spec to the holistic model (DESIGN.md §1)."""
