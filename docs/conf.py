"""Sphinx configuration of the ltca documentation.

Build (from the repository root; ``-W``: any warning fails the build)::

    python3 -m sphinx -W -b html docs docs/_build/html

Generated at build time, never by hand: the example gallery (sphinx-gallery runs ``examples/*.py``), the command
reference (sphinx-argparse reads ``ltca.cli.build_parser``), the validation tables (``_ext/validation_tables.py``
reads ``tests/reference/``), the API pages (autosummary) and the check that ``case_keys.md`` is the output of
``ltca keys --markdown``. ``-D plot_gallery=0`` builds without running the examples.
"""
import os
import sys
from pathlib import Path

DOCS = Path(__file__).resolve().parent
ROOT = DOCS.parent
sys.path.insert(0, str(ROOT))            # the checkout's ltca (and through it ltca.geometry, ltca.fem)
sys.path.insert(0, str(DOCS / "_ext"))
os.environ.setdefault("MPLBACKEND", "Agg")

import ltca  # noqa: E402

project = "ltca"
author = "the ltca authors"
copyright = "the ltca authors, MIT licence"
release = version = ltca.__version__

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.intersphinx",
    "sphinx.ext.mathjax",
    "numpydoc",
    "myst_parser",
    "sphinxarg.ext",
    "sphinx_gallery.gen_gallery",
    "ltca_docs",
]

source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
root_doc = "index"
exclude_patterns = ["_build", "_ext", "_generated", "**.ipynb_checkpoints", "auto_examples/*.md5", "auto_examples/*.py",
                    "auto_examples/*.zip", "auto_examples/*.json", "auto_examples/*.ipynb"]
templates_path = []
html_theme = "alabaster"
smartquotes = False                      # option names such as --torque stay as typed
html_static_path = []
html_title = f"ltca {release}"
html_theme_options = {"description": "Finite-element loaded tooth contact analysis of gears", "fixed_sidebar": True,
                      "page_width": "1180px", "sidebar_width": "240px"}

# Markdown pages (the guide, the design note, case_keys.md): GitHub-flavoured tables, anchors for the headings
myst_enable_extensions = ["colon_fence", "dollarmath"]
myst_heading_anchors = 3

# API reference: numpydoc docstrings; autosummary writes a page per listed name into api/generated/
autosummary_generate = True
autodoc_typehints = "none"
autodoc_member_order = "bysource"
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
numpydoc_validation_checks = set()
numpydoc_xref_param_type = False

intersphinx_mapping = {}                 # no network at build time: cross references stay inside the site
nitpicky = False

sphinx_gallery_conf = {
    "examples_dirs": str(ROOT / "examples"),
    "gallery_dirs": str(DOCS / "auto_examples"),
    "filename_pattern": r"/plot_",
    "within_subsection_order": "FileNameSortKey",
    "download_all_examples": False,
    "remove_config_comments": True,
    "abort_on_example_error": True,
    "only_warn_on_example_error": False,
    "matplotlib_animations": False,
    "image_scrapers": ("matplotlib",),
    "reset_modules": ("matplotlib",),
    "min_reported_time": 1,
    "show_memory": False,
    "show_signature": False,
    "capture_repr": (),
}
