"""`rfc wizard`: a spec built by answering questions, so that nobody writes one by hand.

`prompts` asks (at a terminal, or replaying an answers file), `session` holds the questions and
their defaults, `model` the answers, `emit` writes them as YAML or Python, `stub` writes the
reference stubs the spec names, `write` puts it all on disk and checks it as `rfc check` does.

Layer: below the command line; it may import `rfc.driver` and every layer under it.
"""
