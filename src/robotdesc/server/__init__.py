"""`robotdesc server`: a language server (LSP over stdio, pygls) for .urdf and .xacro files.

session.py lints the top-level descriptions a file belongs to and groups their findings by
the file and line they point to; lsp.py is the pygls protocol layer (diagnostics, code
actions). pygls is the optional extra `robotdesc[lsp]`, imported only by lsp.py.
"""
