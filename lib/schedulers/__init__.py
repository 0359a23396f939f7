"""The six hybrid hardware schedulers of the paper (§6), their models and their composition.

`spec` says what a scheduler is at generation time, `model` simulates it cycle-exactly on
batches of replicates, and the MyHDL blocks (`statechart` plus one module per algorithm family)
generate its hardware. docs/schedulers.md describes the interface and the cycle semantics.
"""
