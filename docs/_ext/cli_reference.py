"""The command-line reference, generated from the tool itself so that it cannot drift.

``.. cli-reference::`` runs ``gpugeom --help``, reads the command names from its "commands:"
list, runs ``gpugeom COMMAND --help`` for each and emits a section per command holding that
text. The tool is the one named by the environment variable GPUGEOM_CLI (scripts/docs.sh sets
it to the build's), else the first ``gpugeom`` on PATH. A command whose help fails, or a tool
that cannot be found, fails the build.
"""
import os
import re
import shutil
import subprocess

from docutils import nodes
from sphinx.errors import ExtensionError
from sphinx.util.docutils import SphinxDirective


def _tool():
    exe = os.environ.get("GPUGEOM_CLI") or shutil.which("gpugeom")
    if not exe or not os.path.exists(exe):
        raise ExtensionError("cli-reference: no gpugeom tool (set GPUGEOM_CLI to the build's "
                             "tools/gpugeom/gpugeom)")
    return exe


def _help(exe, *args):
    r = subprocess.run([exe, *args, "--help"], capture_output=True, text=True, timeout=60)
    text = (r.stdout or r.stderr).rstrip()
    if r.returncode != 0 or not text:
        raise ExtensionError(f"cli-reference: '{' '.join(['gpugeom', *args, '--help'])}' "
                             f"exited {r.returncode}: {r.stderr.strip()}")
    return text


def commands(top_help):
    """The command names of the 'commands:' block of gpugeom --help, in its order."""
    names, inside = [], False
    for line in top_help.splitlines():
        if line.strip() == "commands:":
            inside = True
            continue
        if inside:
            if not line.strip():
                break
            m = re.match(r"\s+([a-z][a-z0-9]*)\b", line)
            if m:
                names.append(m.group(1))
    if not names:
        raise ExtensionError("cli-reference: no 'commands:' list in gpugeom --help")
    return names


class CliReference(SphinxDirective):
    has_content = False

    def run(self):
        exe = _tool()
        top = _help(exe)
        out = [nodes.literal_block(top, top, language="text")]
        for name in commands(top):
            text = _help(exe, name)
            sec = nodes.section(ids=[f"cli-{name}"], names=[f"gpugeom {name}"])
            sec += nodes.title(text=f"gpugeom {name}")
            sec += nodes.literal_block(text, text, language="text")
            self.state.document.note_implicit_target(sec, sec)
            out.append(sec)
        return out


def setup(app):
    app.add_directive("cli-reference", CliReference)
    return {"version": "1", "parallel_read_safe": True}
