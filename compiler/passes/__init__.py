"""The pass pipeline: named steps from the parsed spec to the holistic model.

docs/architecture.md draws the flow.
"""
