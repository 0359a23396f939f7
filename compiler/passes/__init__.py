"""The pass pipeline: named steps from the parsed spec to the holistic model.

docs/architecture.md draws the flow. Layer: below the lowering; it may import the front-ends
(their schema), the HLS interface (`rfc.hls`), the IR, the DSE (for `resolve-scheduler`) and the
layers under them.
"""
