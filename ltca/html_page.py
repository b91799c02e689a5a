"""The self-contained HTML page of a run (``report.html``) for every gear kind: the plots embedded as base64 PNG
and the page rendered by Jinja2 from a kind's ``templates/report.html.j2``. A kind supplies its template and
context (:mod:`ltca.cylindrical.html_report`, :mod:`ltca.bevel.html_report`)."""
from __future__ import annotations

import base64
from pathlib import Path

__all__ = ["embedded_plots", "render_page"]


def embedded_plots(folder: Path, plots) -> list[dict]:
    """The PNG files of ``plots`` ((file name, caption), ...) that exist in ``folder``, as base64 for the page."""
    out = []
    for name, caption in plots:
        f = Path(folder) / name
        if f.exists():
            out.append({"name": name.removesuffix(".png"), "caption": caption,
                        "data": base64.b64encode(f.read_bytes()).decode("ascii")})
    return out


def render_page(package: str, context: dict) -> str:
    """The page's HTML from a context dictionary: ``package``'s ``templates/report.html.j2`` (Jinja2,
    autoescaped, every name the template uses required)."""
    import jinja2
    env = jinja2.Environment(loader=jinja2.PackageLoader(package, "templates"),
                             autoescape=jinja2.select_autoescape(["html", "j2"]), undefined=jinja2.StrictUndefined,
                             trim_blocks=True, lstrip_blocks=True)
    return env.get_template("report.html.j2").render(**context)
