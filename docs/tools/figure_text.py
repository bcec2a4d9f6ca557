"""The smallest text of a figure, written into its PNG, for the browser check.

A PNG does not say how large its text was drawn; the documentation's browser
check (tests/docs_browser_check.py) needs it to tell whether a figure's axis
labels are readable once the page shrinks the image to the column.
:func:`install` wraps matplotlib's ``Figure.savefig`` so that every PNG the
docs build writes (the plot directive's figures and the gallery's) carries a
text chunk ``pendula-min-text-px``: the smallest font size of the figure's
visible, non-empty texts (axis and tick labels, titles, legends, annotations)
in pixels of the saved image, font size (pt) x dpi / 72.  The check scales it
by the width the browser shows the image at over its natural width.
"""

from __future__ import annotations

import pathlib

#: the PNG text chunk's key
KEY = "pendula-min-text-px"


def min_text_px(fig, dpi: float) -> float | None:
    """The smallest font size among the figure's drawn texts, in pixels at ``dpi`` (None: no text)."""
    from matplotlib.text import Text

    fig.draw_without_rendering()   # tick labels get their text when the figure is drawn
    sizes = [t.get_fontsize() for t in fig.findobj(Text)
             if t.get_visible() and t.get_text().strip() and _shown(t)]
    return min(sizes) * dpi / 72.0 if sizes else None


def _shown(t) -> bool:
    """False for a tick label of a tick that is not drawn (outside the view, or a hidden label2)."""
    parent = getattr(t, "axes", None)
    if parent is None:
        return True
    for axis in (parent.xaxis, parent.yaxis):
        for tick in axis.get_major_ticks() + axis.get_minor_ticks():
            if t is tick.label1 or t is tick.label2:
                lo, hi = sorted(axis.get_view_interval())
                loc = tick.get_loc()
                return tick.get_visible() and (loc is None or lo - 1e-9 * abs(hi - lo) <= loc
                                               <= hi + 1e-9 * abs(hi - lo))
    return True


def install() -> None:
    """Make every PNG that ``Figure.savefig`` writes carry :data:`KEY` (idempotent)."""
    import matplotlib
    from matplotlib.figure import Figure

    if getattr(Figure.savefig, "_pendula_text_size", False):
        return
    plain = Figure.savefig

    def savefig(self, fname, *args, **kwargs):
        fmt = kwargs.get("format")
        if fmt is None:
            fmt = (pathlib.Path(str(fname)).suffix[1:] if isinstance(fname, (str, pathlib.PurePath)) else "") \
                or matplotlib.rcParams["savefig.format"]
        if str(fmt).lower() == "png":
            dpi = kwargs.get("dpi") or matplotlib.rcParams["savefig.dpi"]
            if dpi == "figure":
                dpi = self.dpi
            px = min_text_px(self, float(dpi))
            if px is not None:
                kwargs["metadata"] = {**(kwargs.get("metadata") or {}), KEY: f"{px:.3f}"}
        return plain(self, fname, *args, **kwargs)

    savefig._pendula_text_size = True
    Figure.savefig = savefig
