"""`robotdesc expand FILE [name:=value] [-o OUT]`: expand a xacro file to URDF without ROS.

Exit codes: 0 written, 2 the input could not be expanded (or the output is an input).
"""

from __future__ import annotations

import argparse
import dataclasses
import logging
import re
import sys
from typing import Any

from robotdesc.commands.inputs import EXIT_OK, single_input
from robotdesc.expansion import expand_file
from robotdesc.linting.inputs import description_inputs, expansion_inputs
from robotdesc.output import check_output, write_output

log = logging.getLogger(__name__)

#: The root element's name after the prolog (BOM, declaration, comments, whitespace).
_ROOT = re.compile(rb"\A(?:\xef\xbb\xbf)?(?:\s+|<\?.*?\?>|<!--.*?-->)*<([^\s/>]+)", re.S)


def register(subparsers: Any, *, common: argparse.ArgumentParser,
             expansion: argparse.ArgumentParser) -> None:
    """Add the `expand` subcommand."""
    expand = subparsers.add_parser(
        "expand", parents=[common, expansion], help="expand a xacro file to URDF",
        description="Expand a xacro file to URDF without ROS (written to stdout or -o).")
    expand.add_argument("inputs", nargs="+", metavar="FILE | name:=value",
                        help="the xacro file, then xacro arguments")
    expand.add_argument("-o", "--output", metavar="OUT", help="write the URDF to OUT")
    expand.set_defaults(handler=run_expand)


def run_expand(ns: argparse.Namespace) -> int:
    """The handler: expand, then write the readable URDF to stdout or --output."""
    from robotdesc.model.write import urdf_text

    single = single_input(ns, "expand")
    source = single.source
    known = description_inputs(source, single.config.path)
    if ns.output:
        check_output(ns.output, known)
    # as the xacro command: a file that holds substitutions is expanded whatever its name
    options = dataclasses.replace(single.options, substitutions_in_urdf=True)
    expanded = expand_file(source, single.args, options=options)
    urdf = urdf_text(expanded.xml, expanded.source)
    root = _ROOT.match(urdf)
    if root is not None and root.group(1).split(b":")[-1] != b"robot":
        log.warning("note: %s: the root element is <%s>, not <robot>: expanded as xacro would, "
                    "but this is no robot description", source,
                    root.group(1).decode("utf-8", "replace"))
    if not ns.output:
        sys.stdout.buffer.write(urdf)
        sys.stdout.flush()
        return EXIT_OK
    write_output(ns.output, urdf, known + expansion_inputs(expanded))
    log.info("wrote %s (%d bytes)", ns.output, len(urdf))
    return EXIT_OK
