"""Output directories written at once or not at all, shared by every command that writes files.

`rfc.files.directory` replaces rfc's files in a directory from a staging copy in one rename and
`rfc.files.manifest` records which files rfc wrote there, so a rebuild deletes nothing else. It
sits at the bottom of the layers with `rfc.errors`, which is all it imports: the build
(`rfc.lower.writer`), the DSE and the command line write through it.
"""
