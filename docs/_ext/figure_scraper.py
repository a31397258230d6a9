"""A sphinx-gallery image scraper for the pyplot-free figures flumekit returns.

flumekit's figure functions build :class:`matplotlib.figure.Figure` objects without pyplot (safe
in worker processes), so sphinx-gallery's matplotlib scraper, which asks pyplot for its
figures, does not see them. This scraper saves every Figure a code block leaves in the
example's namespace, including the value of a block's last expression, once.
"""

from __future__ import annotations


def figure_scraper(block, block_vars, gallery_conf):
    """Save the Figure objects new in the example's namespace; return their rST."""
    from matplotlib.figure import Figure
    from sphinx_gallery.scrapers import figure_rst

    seen = block_vars.setdefault("flumekit_saved_figures", set())
    paths = []
    for value in list(block_vars["example_globals"].values()):
        if isinstance(value, Figure) and id(value) not in seen:
            seen.add(id(value))
            path = next(block_vars["image_path_iterator"])
            value.savefig(path, dpi=110)
            paths.append(path)
    return figure_rst(paths, gallery_conf["src_dir"])


def _get_sg_image_scraper():
    return figure_scraper
