# Sphinx configuration of gpugeom's documentation site (scripts/docs.sh builds it into
# build/docs/html with warnings as errors). The pages are Markdown (MyST); the Python reference
# comes from the docstrings of the installed package, the C++ reference from the public headers
# (Doxygen's XML through Breathe), the command-line reference from `gpugeom COMMAND --help`, and
# the gallery runs python/examples/ at small sizes on the CPU backend.
import os
import sys
from pathlib import Path

DOCS = Path(__file__).resolve().parent
ROOT = DOCS.parent
sys.path.insert(0, str(DOCS / "_ext"))

project = "gpugeom"
author = "the gpugeom developers"
copyright = "2026, the gpugeom developers"
try:
    import gpugeom

    release = gpugeom.__version__
except ImportError as e:  # the reference needs the package: scripts/docs.sh installs it
    raise RuntimeError("the documentation needs the gpugeom package installed (scripts/docs.sh "
                       "builds and installs it)") from e
version = release

extensions = [
    "myst_parser",
    "sphinx.ext.autodoc",
    "sphinx.ext.napoleon",
    "sphinx.ext.autosummary",
    "sphinx.ext.mathjax",
    "sphinx_gallery.gen_gallery",
    "breathe",
    "cli_reference",
    "bench_plots",
    "reference_coverage",
]

source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
root_doc = "index"
# The logs kept for the developers are not pages of the site.
exclude_patterns = ["_build", "design-notes.md", "performance.md", "auto_examples/*.ipynb",
                    "auto_examples/*.py", "auto_examples/*.zip", "auto_examples/*.md5",
                    "auto_examples/*.json"]
myst_heading_anchors = 3
myst_enable_extensions = ["colon_fence"]
suppress_warnings = [
    "myst.header",  # pages may start at ## under an included title
    # A docstring's type ("array (nsimplex, 3) of int32") names an attribute several classes
    # have; the text is right whichever it would link to. (Broken links in the pages still fail.)
    "ref.python",
    # The C++ reference is one doxygenfile per header, and each declares namespace gpugeom again
    # (Breathe's way); every other entity is declared in exactly one header.
    "duplicate_declaration.cpp",
    # sphinx_gallery_conf holds a function (reset_argv): only incremental rebuilds are affected.
    "config.cache",
]

# Python: the numpydoc-style docstrings, read by napoleon; signatures from the typed stubs.
autodoc_default_options = {"members": True, "undoc-members": False, "show-inheritance": True}
autodoc_member_order = "bysource"
autodoc_typehints = "description"
napoleon_google_docstring = False
napoleon_numpy_docstring = True
napoleon_use_rtype = False
napoleon_use_ivar = True  # Attributes sections as fields: properties documented once

# C++: Doxygen's XML of include/gpugeom (scripts/docs.sh runs Doxygen first).
breathe_projects = {"gpugeom": os.environ.get("GPUGEOM_DOXYGEN_XML",
                                              str(ROOT / "build" / "docs" / "doxygen" / "xml"))}
breathe_default_project = "gpugeom"
breathe_default_members = ("members",)
breathe_show_include = True

# The gallery: every example runs when the docs are built, small and on the CPU executor.
os.environ.setdefault("GPUGEOM_BACKEND", "cpu")
os.environ.setdefault("MPLBACKEND", "Agg")
from gallery_args import example_argv  # noqa: E402

sphinx_gallery_conf = {
    "examples_dirs": str(ROOT / "python" / "examples"),
    "gallery_dirs": "auto_examples",
    "filename_pattern": r"/[a-z][a-z0-9_]*\.py$",
    "ignore_pattern": r"(^|/)_[a-z]",
    "reset_argv": example_argv,
    "download_all_examples": False,
    "remove_config_comments": True,
    "abort_on_example_error": True,
    "only_warn_on_example_error": False,
    "plot_gallery": "True",
    "within_subsection_order": "FileNameSortKey",
}

html_theme = "furo"
html_title = f"gpugeom {release}"
html_static_path = []
nitpicky = False
