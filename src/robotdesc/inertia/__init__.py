"""Inertia: checks of declared `<inertial>` blocks against physics and against the meshes,
and suggested corrections (table, `<inertial>` blocks, a unified-diff patch).

Light to import: `tensor` is pure Python; modules that need numpy import it themselves.
"""
