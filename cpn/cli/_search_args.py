"""What `explore`, its sweep-line mode and `check` share: the arguments as search options and output files, and
the live progress line on a terminal."""

from __future__ import annotations

import time

from cpn.cli._common import prepare_outputs


def explore_outputs(args):
    """The output files `explore` writes, checked before any work (`prepare_outputs`)."""
    return prepare_outputs(("--json", args.json), ("--dot", args.dot), ("--graphml", args.graphml),
                           ("--html", getattr(args, "html", None)), ("--msc", getattr(args, "msc", None)))


def explore_options(args):
    """`explore`'s limits, reduction and back end as `ExploreOptions`."""
    from cpn.statespace import ExploreOptions

    return ExploreOptions(max_states=args.max_states, max_arcs=args.max_arcs, max_seconds=args.max_seconds,
                          max_memory_mb=args.max_memory, time_condensation=args.time_condensation,
                          detect_time_growth=not args.no_time_growth_check,
                          until_time=getattr(args, "until_time", None),
                          reduction=getattr(args, "reduction", None),
                          symmetry=tuple(getattr(args, "symmetric_colour_sets", ()) or ()),
                          backend=getattr(args, "backend", "auto"),
                          workers=getattr(args, "workers", None), ray=getattr(args, "ray", None))


# The fields of the progress line, most important first; those that do not fit the terminal are dropped.
def progress_text(p, width: int) -> str:
    """The progress line for a terminal `width` columns wide: never longer than width - 1 (no wrap)."""
    fields = [f"states {p.states:,}", f"arcs {p.arcs:,}", f"{p.seconds:,.1f} s", f"queue {p.queue:,}",
              f"{p.memory_mb:,.0f} MiB", f"{p.states_per_second:,.0f} states/s"]
    order = [0, 1, 3, 5, 4, 2]  # display order: states, arcs, queue, states/s, MiB, seconds
    limit = max(width - 1, 1)
    # first drop fields (keeping at least two), then the label, then fields again, then cut
    attempts = [("exploring  ", keep) for keep in range(len(fields), 1, -1)]
    attempts += [("", keep) for keep in range(len(fields), 0, -1)]
    for label, keep in attempts:
        line = label + "  ".join(fields[i] for i in order if i < keep)
        if len(line) <= limit:
            return line
    return line[:limit]


class ProgressLine:
    """A rich live line on stderr (states, arcs, queue, states/s, memory), shown after one second and
    fitted to the terminal's width so that it never wraps."""

    def __init__(self):
        self._live = None
        self._console = None
        self._t0 = time.perf_counter()

    def __call__(self, p) -> None:
        if self._live is None:
            if p.seconds < 1.0:
                return
            from rich.console import Console
            from rich.live import Live

            self._console = Console(stderr=True)
            self._live = Live("", console=self._console, transient=True, auto_refresh=False)
            self._live.start()
        from rich.text import Text

        line = progress_text(p, self._console.width)
        text = Text(line, no_wrap=True, overflow="crop")
        if line.startswith("exploring"):
            text.stylize("bold", 0, len("exploring"))
        self._live.update(text, refresh=True)

    def close(self) -> None:
        if self._live is not None:
            self._live.stop()
            self._live = None


__all__ = ["ProgressLine", "explore_options", "explore_outputs", "progress_text"]
