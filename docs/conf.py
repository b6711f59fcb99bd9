# Sphinx configuration of mdrmap's user guide (docs/*.md, MyST Markdown).
# Build: python3 -m sphinx -W -b html docs build/docs-html (the test docs_site).
project = "mdrmap"
author = "the mdrmap authors"
extensions = ["myst_parser"]
source_suffix = {".md": "markdown"}
root_doc = "index"
# docs/examples holds Python examples (run by the tests), not pages.
exclude_patterns = ["_build", "examples"]
# Anchors for the headings, as GitHub makes them, so that links like
# design.md#load-control work on GitHub and in the site alike.
myst_heading_anchors = 4
html_theme = "furo"
html_title = "mdrmap"
# Code blocks without a language (CSV, INI excerpts, output) are not highlighted.
highlight_language = "none"
# Smart quotes, but no dashes: "--prony" in a table or in prose is an option,
# never an en dash.
smartquotes_action = "qe"
