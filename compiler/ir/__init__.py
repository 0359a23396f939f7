"""The IR: a typed data-flow graph with source locations, its text form and its invariants.

Layer: below the front-ends, beside `rfc.dse` (neither imports the other); it may import the
message layer and the layers under it.
"""
