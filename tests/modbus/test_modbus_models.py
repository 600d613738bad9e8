"""The MODBUS, mMODBUS and Modbus-A models: key figures and the thesis's claims on small scenarios.

The claims are checked here in Python over the explored graph (markings without time stamps), so that
the models are guarded whatever the state of the scenario checker; specs/modbus/ states the same
properties in the scenario format.
"""

import os
import tomllib

import pytest

import cpn
from cpn.statespace import Explorer
from cpn.statespace.scc import strongly_connected_components

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
MODBUS = os.path.join(ROOT, "models", "modbus", "modbus.cpnet")
MODBUS_A = os.path.join(ROOT, "models", "modbus", "modbus_a.cpnet")
SPECS = os.path.join(ROOT, "specs", "modbus")

# record fields in value order (sorted by label): adr, exc, fc, id, ok, qty, reg, src
ADR, EXC, FC, ID, OK, QTY, REG, SRC = range(8)
# union constructors in declaration order: OUT = Answer | NoAnswer | Sent; MST = Idle | Ready | ... | ProcError
ANSWER, NO_ANSWER, SENT = range(3)
A2 = {"CONFIG": '"A"', "ADRS": "[0,3,5,6]", "FCS": "[1,7,20]", "PO": "2", "CRC": "1"}
D2 = {"CONFIG": '"D"', "ADRS": "[3,5]", "FCS": "[1,7,20,65]", "PO": "2"}


class Explored:
    def __init__(self, path, sets, time_condensation=True, reference=False):
        self.model = cpn.load(path, set=sets)
        self.engine = self.model.engine(time_condensation=time_condensation, reference=reference)
        self.x = Explorer(self.engine).run()
        assert self.x.complete
        self.g = self.x.graph
        self.place = {p.name: i for i, p in enumerate(self.model.net.places)}

    def view(self, s, name):
        p = self.place[name]
        if hasattr(self.engine, "place_view"):
            return self.engine.place_view(s, p)
        ms = self.engine.marking(s)[p]
        out = {}
        for v, k in ms.items():
            v = v[0] if self.model.net.places[p].timed else v
            out[v] = out.get(v, 0) + k
        return out

    def only(self, s, name):
        (v,) = self.view(s, name)
        return v

    def states(self):
        return (self.g.states[i] for i in range(self.g.n_states))

    def dead(self):
        return [self.g.states[i] for i in self.g.dead_states()]

    def dead_modulo_time(self):
        return len({self.engine.untimed(s) for s in self.dead()})

    def has_cycle(self):
        return any(strongly_connected_components(self.g.n_states, self.g.offsets, self.g.dst).nontrivial)

    def fired(self, transition):
        names = {self.engine.binding_element(be).transition for be in self.g.bes}
        return any(self.engine.transitions[t].name == transition for t in names)


def _waiting_reply(state, sends=None):
    """The master's state is WaitReply {f, sends} (the fourth constructor of MST), with that many sends."""
    return isinstance(state, tuple) and state[0] == 3 and (sends is None or state[1][1] == sends)


def slave_frames(e, s):
    return [f for name in ("Modbus's2b 1", "Modbus'b2m 1") for f in e.view(s, name) if f[SRC] != 0]


@pytest.fixture(scope="module")
def a2():
    return Explored(MODBUS, A2)


def test_a2_key_figures(a2):
    # python -m cpn explore models/modbus/modbus.cpnet --time-condensation --set 'ADRS=[0,3,5,6]' \
    #   --set 'FCS=[1,7,20]' --set CRC=1
    assert (a2.g.n_states, a2.g.n_arcs, len(a2.g.dead_states())) == (1042, 1289, 3)


def test_a2_claims_and_the_protocol_rules(a2):
    frames = [(0, c) for c in (1, 7, 20)] + [(a, c) for a in (3, 5, 6) for c in (1, 7, 20)]
    adrs = {1: {3}, 2: {5}}
    for s in a2.states():
        # claim 1: one master state, every slave in one state of Fig. 8
        assert sum(a2.view(s, "Master'State 1").values()) == 1
        for k in (1, 2):
            busy = sum(sum(a2.view(s, f"Slave'{p} {k}").values())
                       for p in ("Idle", "Processing", "FormatNormal", "FormatError", "WaitEvent"))
            assert busy == 1
            # S2: a slave acts only on a good frame for its address or a broadcast
            for name in ("Processing", "FormatNormal", "FormatError"):
                for (who, f) in a2.view(s, f"Slave'{name} {k}"):
                    assert who == k and f[OK] and (f[ADR] == 0 or f[ADR] in adrs[k])
        # claim 2: nothing is fetched or sent before the previous transaction is closed
        done = sum(a2.view(s, "Master'Done 1").values())
        assert a2.only(s, "Master'NextId 1") - 1 <= done + 1
        assert all(f[ID] <= done + 1 for f in a2.view(s, "Modbus'm2b 1"))
        # S-P4: no reply to a broadcast; replies carry the requested address
        for f in slave_frames(a2, s):
            adr_req, fc_req = frames[f[ID] - 1]
            assert adr_req != 0 and f[ADR] == adr_req and f[FC] in (fc_req, fc_req + 128)
        # the master delivers only good replies that answer the request
        for (kind, v) in a2.view(s, "Master'Done 1"):
            if kind == ANSWER:
                i, p = v
                assert p[OK] and p[ID] == i and (p[ADR], p[FC] & 127) == frames[i - 1]
        # one frame on the line
        assert sum(a2.view(s, "Modbus'm2b 1").values()) + sum(a2.view(s, "Modbus's2b 1").values()) <= 1


def test_every_frame_reaches_every_slave_and_each_filters_it(a2):
    # before, the bus gave a copy only to the owner, so S2 (not for this slave) was dead
    assert a2.fired("Slave'Discard 1") and a2.fired("Slave'Discard 2")
    rounds = {tuple(ks) for s in a2.states() for (ks, f) in a2.view(s, "Modbus'b2s 1") if f[SRC] == 0 and f[ID] > 3}
    assert (1, 2) in rounds  # a unicast frame's round starts at slave 1 whatever its address


def test_late_slave_races_the_timeout_and_the_retry(a2):
    # slave 1 may take TLATE > RESP_TO: the time-out, the retry (lost by the busy slave)
    # and a reply arriving during the retry are all reachable
    assert a2.fired("Master'ResponseTimeout 1") and a2.fired("Master'Retry 1")
    assert a2.fired("Slave'Lost 1")
    late_answer = any(
        _waiting_reply(a2.only(s, "Master'State 1"), sends=2) and any(f[SRC] == 1 for f in a2.view(s, "Modbus'b2m 1"))
        for s in a2.states())
    assert late_answer


def test_stale_reply_during_the_next_transaction_is_not_the_answer():
    # PO 0: the master gives up on slave 1's late frame and moves on; the late reply arrives while it waits
    # for the next frame's reply (M4 unexpected), and is never delivered as that frame's answer
    e = Explored(MODBUS, {**A2, "PO": "0"})
    assert e.fired("Master'ReplyUnexpected 1")
    stale = False
    for s in e.states():
        st = e.only(s, "Master'State 1")
        if _waiting_reply(st):
            pending = st[1][0]
            stale |= any(f[SRC] != 0 and f[ID] != pending[ID] for f in e.view(s, "Modbus'b2m 1"))
        for (kind, v) in e.view(s, "Master'Done 1"):
            assert kind != ANSWER or v[1][ADR] == [0, 0, 0, 3, 3, 3, 5, 5, 5, 6, 6, 6][v[0] - 1]
    assert stale


def test_corrupted_frames_are_discarded_by_slaves_and_frame_errors_at_the_master(a2):
    # a corrupted frame reaches every slave (each discards it) and the master (M8)
    assert a2.fired("Bus'CorruptMaster 1") and a2.fired("Bus'CorruptSlave 1")
    assert a2.fired("Master'FrameError 1")
    seen = {k for s in a2.states() for (ks, f) in a2.view(s, "Modbus'b2s 1") if not f[OK] for k in ks}
    assert seen == {1, 2}


def test_retries_matter_timed_states_and_dead_markings_grow_with_po():
    # the thesis's trend A.3 (PO 0) < A.2 (PO 2) < A.4 (PO 5), in states and dead markings,
    # on the timed state space (CPN Tools' figures); the old model had 221 / 311 / 446 states and 3 dead
    # markings each
    figures = []
    for po in (0, 2, 5):
        e = Explored(MODBUS, {**A2, "PO": str(po)}, time_condensation=False)
        figures.append((e.g.n_states, len(e.g.dead_states())))
    assert figures == [(2960, 61), (11560, 106), (19543, 118)]
    assert figures[0] < figures[1] < figures[2] and figures[0][1] < figures[1][1] < figures[2][1]


def test_a2_claim_4_every_dead_marking_is_the_end_and_no_cycle(a2):
    for d in a2.dead():
        assert sum(a2.view(d, "Master'Done 1").values()) == 12
        assert {(v if k != ANSWER else v[0]) for (k, v) in a2.view(d, "Master'Done 1")} == set(range(1, 13))
        assert a2.view(d, "Master'Queue 1") == {(): 1}
        for name in ("Modbus'm2b 1", "Modbus'b2m 1", "Modbus's2b 1", "Modbus'b2s 1", "Master'Timer 1"):
            assert not a2.view(d, name)
    assert not a2.has_cycle()
    # adr 6 has no slave: 1 + PO sends, then the error path
    assert a2.fired("Master'GiveUp 1")


def test_reference_interpreter_agrees_on_a1():
    # scenario A has two slaves: with MAXS = 2 the net has only their instances, the same state space, and
    # the reference interpreter explores it in a tenth of the time the 16 idle instances cost it
    sets = {"ADRS": "[3,5]", "FCS": "[4,5,7]", "CRC": "1"}
    compiled, reference = Explored(MODBUS, sets), Explored(MODBUS, {**sets, "MAXS": "2"}, reference=True)
    compiled2 = Explored(MODBUS, {**sets, "MAXS": "2"})
    assert (compiled.g.n_states, compiled.g.n_arcs) == (reference.g.n_states, reference.g.n_arcs) == (821, 1076)
    assert (compiled2.g.n_states, compiled2.g.n_arcs) == (821, 1076)


def test_multislave_answers_with_the_requested_address():
    e = Explored(MODBUS, {"CONFIG": '"C"', "S2ADRS": "[5,6]", "ADRS": "[3,5,6]", "FCS": "[7]", "PO": "0"})
    replies = {(f[SRC], f[ADR]) for s in e.states() for f in e.view(s, "Modbus'b2m 1")}
    assert replies == {(1, 3), (2, 5), (2, 6)}


def test_superslave_answers_by_broadcast_within_its_window_and_the_others_process_it():
    e = Explored(MODBUS, D2)
    super_frames = set()
    for s in e.states():
        assert sum(e.view(s, "Slave'WaitEvent 1").values()) == sum(e.view(s, "Slave'Window 1").values())
        super_frames |= {(f[SRC], f[ADR]) for f in slave_frames(e, s) if f[FC] in (65, 65 + 128)}
    assert super_frames == {(1, 0), (2, 5)}  # SuperSlave: broadcast; standard slave: exception (SS-P7)
    assert e.fired("Slave'WindowExpired 1") and e.fired("Master'SuperAnswer 1") and e.fired("Master'T2Expired 1")
    assert e.fired("Slave'AcceptBroadcast 2")  # slave 2 processes the SuperSlave's broadcast (SS-P6)
    assert not e.has_cycle()


@pytest.mark.parametrize("sets,broken", [
    ({**D2, "MUTANT": '"super-no-t2"'}, "frame to a slave processing a broadcast"),
    ({"ADRS": "[0,3]", "FCS": "[1]", "MUTANT": '"bcast-reply"', "BCAST_ANY": "true"}, "reply to broadcast"),
    ({"ADRS": "[3,5]", "FCS": "[4]", "MUTANT": '"early-send"'}, "early send"),
    ({"ADRS": "[3,5]", "FCS": "[4]", "CRC": "1", "MUTANT": '"no-address-filter"'}, "foreign frame"),
    ({"ADRS": "[3,5]", "FCS": "[4]", "CRC": "1", "MUTANT": '"slave-ignores-crc"'}, "foreign frame"),
])
def test_mutants_are_caught(sets, broken):
    e = Explored(MODBUS, sets)
    found = set()
    cfg = {1: {3}, 2: {5}}
    for s in e.states():
        # a reply to a broadcast (frame 1 of ADRS [0,3] x FCS [1]); the slave puts its own address in it
        if "ADRS" in sets and sets["ADRS"].startswith("[0") and any(f[ID] == 1 for f in slave_frames(e, s)):
            found.add("reply to broadcast")
        if e.only(s, "Master'NextId 1") - 1 > sum(e.view(s, "Master'Done 1").values()) + 1:
            found.add("early send")
        for k in (1, 2):
            for place in ("Processing", "FormatNormal", "FormatError"):
                if any(not f[OK] or (f[ADR] != 0 and f[ADR] not in cfg[k]) for (_, f) in e.view(s, f"Slave'{place} {k}")):
                    found.add("foreign frame")
        bcast = {k for k in (1, 2) for (_, f) in e.view(s, f"Slave'Processing {k}") if f[ADR] == 0}
        if any(f[SRC] == 0 and set(ks) & bcast for (ks, f) in e.view(s, "Modbus'b2s 1")):
            found.add("frame to a slave processing a broadcast")
    assert broken in found


def _modbus_a(**sets):
    return Explored(MODBUS_A, {k: str(v) for k, v in sets.items()})


def test_modbus_a_allocates_ids_by_position():
    # python -m cpn explore models/modbus/modbus_a.cpnet --time-condensation --set N=4
    e = _modbus_a(N=4)
    assert (e.g.n_states, e.g.n_arcs, e.dead_modulo_time()) == (81, 84, 1)
    (d,) = e.dead()
    assert e.view(d, "Chain'Slaves 1") == {(k, 0, k): 1 for k in range(1, 5)}  # (position, Default, ID)
    assert e.only(d, "Master'Stats 1") == (1, 5, 4)  # 1 reset, N + 1 configurations, N acks
    assert e.only(d, "Master'PollLog 1") == ((0, 0), (4, 1), (3, 1), (2, 1), (1, 1))
    assert not e.has_cycle()


@pytest.mark.parametrize("sets,duplicate,all_allocated", [
    ({"E3": "true", "ACK_POLICY": '"same"'}, True, False),
    ({"E3": "true", "ACK_POLICY": '"stop"'}, False, False),
    ({"E3": "true", "ACK_POLICY": '"next"'}, False, True),
    ({"E1": "true"}, True, False),
    ({"MUTANT": '"forward-config"'}, True, False),
])
def test_modbus_a_faults_break_the_expected_properties(sets, duplicate, all_allocated):
    e = _modbus_a(N=3, **sets)
    dup = any(len([i for (_, mode, i) in e.view(s, "Chain'Slaves 1") if mode == 0 and i > 0])
              != len({i for (_, mode, i) in e.view(s, "Chain'Slaves 1") if mode == 0 and i > 0})
              for s in e.states() if e.only(s, "Master'Phase 1") not in (0, 1))
    allocated = all(e.view(d, "Chain'Slaves 1") == {(k, 0, k): 1 for k in (1, 2, 3)} for d in e.dead())
    assert dup == duplicate
    assert allocated == all_allocated


def test_scenario_files_name_existing_models_and_properties():
    files = [os.path.join(d, f) for d, _, fs in os.walk(SPECS) for f in fs if f.endswith(".toml")]
    assert len(files) >= 17 + 2 + 18
    for path in files:
        with open(path, "rb") as fh:
            scenario = tomllib.load(fh)
        model = os.path.normpath(os.path.join(os.path.dirname(path), scenario["model"]))
        assert os.path.exists(model), path
        assert scenario["property"], path
        for prop in scenario["property"]:
            # a MODBUS.md property, or a path the configuration excludes (a protocol fact, bench/modbus.py DEAD);
            # the TCP files: the rules T1-T6 and MBAP of docs/modbus_tcp.md, and the seed's conflict as a finding
            serial = ("S-P", "M-P", "SS-P", "MA", "dead (a protocol fact")
            tcp = tuple(f"T{i}{c}" for i in range(1, 7) for c in ": ") + ("MBAP:", "finding (")
            names = tcp if os.path.basename(path).startswith("tcp") else serial
            assert prop["name"].startswith(names), (path, prop["name"])


def test_modbus_a_42_slaves_reproduces_the_papers_checkpoints():
    # MODBUS.md 4.3: after the 9th, 18th, 30th and 44th iteration (message of the master), 8, 17, 29 and
    # all 42 slaves are configured; here on the full state space of the 42-slave chain
    e = _modbus_a(N=42)
    configured_after = {}
    for s in e.states():
        resets, configs, acks = e.only(s, "Master'Stats 1")
        phase = e.only(s, "Master'Phase 1")
        if isinstance(phase, tuple) and phase[0] == 3:  # WaitAck: iteration resets + configs is in flight
            continue
        n = sum(1 for (_, mode, i) in e.view(s, "Chain'Slaves 1") if mode == 0 and i > 0)
        configured_after.setdefault(resets + configs, set()).add(n)
    assert {i: configured_after[i] for i in (9, 18, 30, 44)} == {9: {8}, 18: {17}, 30: {29}, 44: {42}}
    assert max(configured_after) == 44


def test_exceptions_01_02_03_04_in_the_specs_order():
    e = Explored(MODBUS, {"EXTRA": "[(3, 3, 99, 1), (3, 3, 1, 200), (5, 1, 1, 1), (5, 4, 6, 1)]", "FAIL_FCS": "[4]",
                          "LATE": "[]"})
    replies = {(f[ADR], f[FC], f[EXC]) for s in e.states() for f in e.view(s, "Modbus'b2m 1")}
    assert replies == {(3, 133, 1), (3, 135, 1), (5, 133, 1),   # unsupported codes 5, 7
                       (3, 131, 2),                             # register 99 is not Slave1's
                       (3, 131, 3),                             # quantity 200 > 125
                       (5, 129, 1),                             # code 1 and register 1: the code first
                       (3, 132, 4), (5, 132, 4),                # code 4 fails while processing (S7)
                       (5, 7, 0)}


def test_frames_in_any_order_each_sent_once():
    # the other reading of the thesis's generator (MODBUS.md 3.6 item 14), the timed state space
    # python -m cpn explore models/modbus/modbus.cpnet --set 'ADRS=[3,5]' --set 'FCS=[4,7]' --set 'ORDER="any"'
    e = Explored(MODBUS, {"ADRS": "[3,5]", "FCS": "[4,7]", "ORDER": '"any"'}, time_condensation=False)
    assert (e.g.n_states, e.g.n_arcs, len(e.dead())) == (3777, 4313, 31)
    for d in e.dead():
        assert not e.view(d, "Master'Pending 1") and sum(e.view(d, "Master'Done 1").values()) == 4
        assert e.view(d, "Master'State 1") == {0: 1}  # Idle
        for name in ("Modbus'm2b 1", "Modbus'b2m 1", "Modbus's2b 1", "Modbus'b2s 1"):
            assert not e.view(d, name)
    assert not e.has_cycle()


def test_modbus_a_loads_long_chains():
    # the initial marking of 200 slaves (range was a recursive CPN ML function: it failed past
    # about 100 slaves); the reset then travels the whole chain
    model = cpn.load(MODBUS_A, set={"N": "200", "MAXN": "200"})
    engine = model.engine(time_condensation=True)
    x = Explorer(engine, cpn.statespace.ExploreOptions(time_condensation=True, max_states=250)).run()
    assert x.n_states == 250
