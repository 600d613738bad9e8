"""Reports: the standard report as data (`model`) and its renderers (text, JSON, graph exports, HTML).

May import cpn.checks and cpn.statespace; never cli.
"""

from cpn.report.json import to_json
from cpn.report.model import Report, build_report
from cpn.report.text import render_text

__all__ = ["Report", "build_report", "render_text", "to_json"]
