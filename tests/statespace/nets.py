"""Small hand-worked toy nets for the report tests (each docstring gives the expected answers)."""

from _toy import Mode, ToyEngine, ToyPlace, ToyTransition, pt_net


def two_terminal_sccs():
    """P0 -> (T0) P1 <-> P3 cycle (T2, T3); P0 -> (T1) P2 dead.

    States: 1 {P0}, 2 {P1}, 3 {P2} (dead), 4 {P3}. Terminal SCCs {2,4} and {3}: no home marking, no
    live transition. Fairness: T2, T3 impartial; T0, T1 fair (never enabled on the cycle).
    """
    pre = [[1, 0, 0, 0], [1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 0, 1]]
    post = [[0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1], [0, 1, 0, 0]]
    return pt_net(pre, post, [1, 0, 0, 0], tnames=["T0", "T1", "T2", "T3"], pnames=["P0", "P1", "P2", "P3"])


def livelock():
    """A -(Start)-> B; B -(Spin)-> B (self-loop); B -(Exit)-> C (dead).

    Spin impartial (the only cycle), Exit has no fairness (continuously enabled on the spin loop),
    Start fair. One dead marking; home marking = the dead one.
    """
    pre = [[1, 0, 0], [0, 1, 0], [0, 1, 0]]
    post = [[0, 1, 0], [0, 1, 0], [0, 0, 1]]
    return pt_net(pre, post, [1, 0, 0], tnames=["Start", "Spin", "Exit"], pnames=["A", "B", "C"])


def just_net():
    """u: A -> B, v: B -> A (a cycle); t: A + X -> A + Y, once.

    On the cycle (A,X) -> (B,X) -> (A,X) t is enabled in (A,X) only: t is just, not fair.
    u and v: no fairness? Removing u leaves no cycle: u and v are impartial.
    """
    pre = [[1, 0, 0, 0], [0, 1, 0, 0], [1, 0, 1, 0]]
    post = [[0, 1, 0, 0], [1, 0, 0, 0], [1, 0, 0, 1]]
    return pt_net(pre, post, [1, 0, 1, 0], tnames=["u", "v", "t"], pnames=["A", "B", "X", "Y"])


def coloured_register():
    """Place R of colour set STR holds "c" always and one of "a"/"b": Flip a->b, Flop b->a.

    Bounds of R: integer 2/2, upper multiset 1`"a"++1`"b"++1`"c", lower 1`"c". Home markings: all.
    """
    places = [ToyPlace("Top'R 1", "STR")]
    modes = [Mode(0, {"x": '"a"'}, {0: {"a": 1}}, {0: {"b": 1}}),
             Mode(1, {"x": '"b"'}, {0: {"b": 1}}, {0: {"a": 1}})]
    return ToyEngine(places, [ToyTransition("Top'Flip 1"), ToyTransition("Top'Flop 1")], modes,
                     [{"a": 1, "c": 1}])


def timed_merge():
    """Timed: Start consumes P@0 and puts Q@+1 (Fast) or Q@+2 (Slow): two dead markings, one modulo time."""
    places = [ToyPlace("Top'P 1", "UNIT", timed=True), ToyPlace("Top'Q 1", "UNIT", timed=True)]
    modes = [Mode(0, {}, {0: {(): 1}}, {1: {(): 1}}, delay=1), Mode(1, {}, {0: {(): 1}}, {1: {(): 1}}, delay=2)]
    return ToyEngine(places, [ToyTransition("Top'Fast 1"), ToyTransition("Top'Slow 1")], modes,
                     [{((), 0): 1}, {}], is_timed=True)


def timed_cycle():
    """Timed, all delays 0: A@0 -> (Go) B@0 -> (Back) A@0: the initial marking is a home marking."""
    places = [ToyPlace("Top'A 1", "UNIT", timed=True), ToyPlace("Top'B 1", "UNIT", timed=True)]
    modes = [Mode(0, {}, {0: {(): 1}}, {1: {(): 1}}), Mode(1, {}, {1: {(): 1}}, {0: {(): 1}})]
    return ToyEngine(places, [ToyTransition("Top'Go 1"), ToyTransition("Top'Back 1")], modes,
                     [{((), 0): 1}, {}], is_timed=True)


def counter():
    """An unbounded counter (T0 adds a token to P0 for ever): only partial searches end."""
    return pt_net([[0]], [[1]], [0])
