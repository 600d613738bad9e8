"""MODBUS/TCP and the gateway (models/modbus/modbus_tcp.cpnet): the scenario files and the scale table.

Usage:
  python bench/modbus_tcp.py --write-specs     # specs/modbus/tcp*.toml and specs/modbus/mutants/tcp_*.toml
  python bench/modbus_tcp.py --mutants          # the mutant table of reports/README.md (MODBUS/TCP)
  python bench/modbus_tcp.py --scale [--budget 120] [--rows small|all|gateway]
                                               # C x S x depth (plain servers) and C x depth x NS (gateway):
                                               # the full state space, the quotient by the symmetry of the
                                               # Client and Server instances, and the sweep-line on the clock

Every scenario file carries the whole TCP property set (PROPERTIES); a mutant file is the same with the
model's TMUTANT switch set and `expect = "violated"` on the properties its bug must break. The --scale
form explores each configuration with `python -m cpn explore models/modbus/modbus_tcp.cpnet --set ...`
four ways (time condensation; time condensation and --reduction symmetry; --sweep-line without
condensation, the clock as the progress measure; --sweep-line with condensation and PROGRESS as the
measure) and prints the table of reports/README.md ("MODBUS/TCP and the gateway").
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MODEL = os.path.join(ROOT, "models", "modbus", "modbus_tcp.cpnet")
SPECS = os.path.join(ROOT, "specs", "modbus")

# ---------------------------------------------------------------------------------------------- properties
#: (key, name, kind, fields): the TCP property set; `key` names it in MUTANTS
#: the helpers of the property texts: a predicate of every (some) element of a multiset, written so that
#: symmetry reduction decides the text (ms_to_list only inside list_to_ms (List.map F (ms_to_list M)))
ALLOF = "fun allOf (p0, m0) = cf (false, list_to_ms (List.map p0 (ms_to_list m0))) = 0"
ANYOF = "fun anyOf (p0, m0) = cf (true, list_to_ms (List.map p0 (ms_to_list m0))) > 0"
DISTINCT = "fun distinct [] = true | distinct (h :: rest0) = not (mem rest0 h) andalso distinct rest0"

PROPERTIES: list[tuple[str, str, str, dict]] = [
    ("tid-connection",
     "T1: every response on a connection is for its client and carries the transaction id of a request that "
     "client sent on that connection",
     "invariant", {"expr": f"""let {ALLOF}
in allOf ((fn (w, nd, z, l) => List.all (fn (a : ADU) => #who a = w andalso cf ((w, nd, z, #tid a), sum Client'Sent) > 0) l),
ModbusTCP's2c 1) end"""}),
    ("match",
     "T1: a client takes a response as the answer only to the outstanding request with its transaction id, "
     "and the response echoes that request",
     "invariant", {"expr": f"""let {ALLOF}
in allOf ((fn d => case d of
    Answered ((nd, z, q : ADU), r : ADU) => #tid r = #tid q andalso #who r = #who q andalso #unit r = #unit q
      andalso #reg r = #reg q andalso (#fc r = #fc q orelse #fc r = #fc q + 128)
      andalso (#fc q <> 6 orelse #exc r > 0 orelse #v r = #v q)
  | _ => true), sum Client'Done) end"""}),
    ("depth",
     "T2: a client never has more than DEPTH requests outstanding",
     "invariant", {"expr": f"""let {ALLOF}
in forall Client'Out (fn m => allOf ((fn o => length o <= DEPTH), m)) end"""}),
    ("tid-unique",
     "T6: transaction ids are not reused while outstanding: a client's outstanding requests have distinct ids",
     "invariant", {"expr": f"""let {ALLOF}
    {DISTINCT}
in forall Client'Out (fn m => allOf ((fn o => distinct (List.map (fn (n9, z9, a : ADU) => #tid a) o)), m)) end"""}),
    ("no-duplicate",
     "T3: no response is duplicated: each transaction id of a connection is received (or in flight to its "
     "client) at most once",
     "invariant", {"expr": f"""let {ALLOF}
    val got = sum Client'Got
in allOf ((fn g => cf (g, got) = 1), got) andalso
allOf ((fn (w, nd, z, l) => List.all (fn (a : ADU) => cf ((w, nd, z, #tid a), got) = 0 andalso
  length (List.filter (fn (b : ADU) => #tid b = #tid a) l) = 1) l), ModbusTCP's2c 1) end"""}),
    ("no-loss",
     "T3: no response is lost while its connection stays open: when the protocol stops, every request sent "
     "on a connection still open has had its response",
     "dead_markings", {"expr": f"""let {ALLOF}
in allOf ((fn (w, nd, z, t0) => cf ((w, nd, z), ModbusTCP'conn 1) = 0 orelse cf ((w, nd, z, t0), sum Client'Got) > 0),
sum Client'Sent) end"""}),
    ("one-outcome",
     "T4: a request has at most one outcome (answered, timed out or aborted)",
     "invariant", {"expr": f"""let {ALLOF}
    fun tidOf d = case d of Answered ((n9, z9, q : ADU), r9) => #tid q | TimedOut t0 => t0 | Aborted t0 => t0
in forall Client'Done (fn m => let val tids = list_to_ms (List.map tidOf (ms_to_list m))
  in allOf ((fn t0 => cf (t0, tids) = 1), tids) end) end"""}),
    ("done",
     "T4: when the protocol stops, every request of every client has its outcome, nothing is outstanding or "
     "in flight, and every server and the gateway is idle",
     "dead_markings", {"expr": f"""let {ALLOF}
in forall Client'Todo (fn m => m = 1`[]) andalso forall Client'Out (fn m => m = 1`[]) andalso
forall Client'Next (fn m => size m = 0) andalso size (sum Client'Done) = NC * NSCRIPT andalso
allOf ((fn (w9, n9, z9, l) => l = []), ModbusTCP'c2s 1) andalso allOf ((fn (w9, n9, z9, l) => l = []), ModbusTCP's2c 1)
andalso size (ModbusTCP'resp 1) = 0 andalso forall Server'Busy (fn m => m = 1`0) andalso
Gateway'State 1 = 1`GIdle andalso Gateway'Queue 1 = 1`[] end"""}),
    ("eventually",
     "T4 (CTL): on every path, every request is eventually answered, answered with an exception, timed out "
     "or aborted",
     "ctl", {"formula": """AF (size (sum Client'Done) = NC * NSCRIPT andalso forall Client'Out (fn m => m = 1`[]))"""}),
    ("eventually-ltl",
     "T4 (LTL): every request sent is eventually answered, answered with an exception, timed out or aborted",
     "ltl", {"formula": """G (F (size (sum Client'Done) = size (sum Client'Sent) andalso forall Client'Out (fn m => m = 1`[])))"""}),
    ("no-livelock",
     "T4: no infinite loop (the state space has no cycle)",
     "no_livelock", {}),
    ("mbap",
     "MBAP: every ADU on a connection has protocol id 0 and a length that counts the unit id and the PDU",
     "invariant", {"expr": f"""let {ALLOF}
    fun reqOk (a : ADU) = #pid a = 0 andalso #len a = 6
    fun rspOk (a : ADU) = #pid a = 0 andalso #len a = (if #exc a > 0 then 3 else if #fc a = 3 then 5 else 6)
in allOf ((fn (w9, n9, z9, l) => List.all reqOk l), ModbusTCP'c2s 1) andalso
allOf ((fn (w9, n9, z9, l) => List.all rspOk l), ModbusTCP's2c 1) end"""}),
    ("gw-one",
     "T5: the gateway has at most one transaction on the serial line (SL 2.4.1: one transaction at a time)",
     "bound", {"place": "Gateway'State 1", "at_most": 1}),
    ("gw-line",
     "T5: no serial frame reaches a slave still busy with another request (the line carries one "
     "transaction at a time)",
     "invariant", {"expr": """not (enabled "Slave'Lost")"""}),
    ("gw-codes",
     "T5: the gateway answers 0A exactly for a unit id it does not route, 0B exactly when the target did not "
     "respond to 1 + GW_PO sends, and carries every slave's reply back",
     "invariant", {"expr": f"""let {ALLOF}
in allOf ((fn (u0, f0, e0, n0) =>
  if not (mem ROUTE u0) then e0 = 10 andalso n0 = 0
  else if owners u0 = [] then e0 = 11 andalso n0 = GW_PO + 1
  else e0 <> 10 andalso e0 <> 11 andalso n0 >= 1), Gateway'Log 1) end"""}),
    ("all-answered",
     "T4: every request can be answered (a run with no time-out and no abort)",
     "reachable", {"expr": f"""let {ALLOF}
in size (sum Client'Done) = NC * NSCRIPT andalso allOf ((fn d => case d of Answered _ => true | _ => false),
sum Client'Done) end"""}),
    ("contradictory-writes",
     "finding (the seed: 'Is it possible to have conflicts with clients making contradictory requests of a "
     "particular server? Yes'): two clients' writes of different values to one register are both confirmed",
     "reachable", {"expr": f"""let {ANYOF}
    fun write d = case d of
        Answered ((nd, z9, q : ADU), r : ADU) => (#fc q = 6 andalso #exc r = 0, nd, #v q)
      | _ => (false, Gw, Init)
    val w = list_to_ms (List.map write (ms_to_list (sum Client'Done)))
in anyOf ((fn (ok1, n1, v1) => ok1 andalso anyOf ((fn (ok2, n2, v2) => ok2 andalso n1 = n2 andalso v1 <> v2), w)),
w) end"""}),
]

ALL = [p[0] for p in PROPERTIES]
#: properties about the plain servers' shared register (only meaningful with two clients that write)
WRITES = ["contradictory-writes"]

# ---------------------------------------------------------------------------------------------- scenarios
SRV_SCRIPT = "[(AnySrv, 255, 6, 1), (AnySrv, 255, 3, 1)]"
COMMON = {"LATE": "([] : INT list)", "TPROC": "[1]", "CRC": "0"}


SCENARIOS = [
    # (file, name, description, set, rows, properties left out)
    ("tcp.toml", "TCP",
     "Modbus/TCP clients writing and reading one register of any of NSV plain servers: C x S x depth, one and "
     "several requests in progress per server",
     {**COMMON, "SCRIPTS": '"servers"'},
     [{"NC": 2, "NSV": 1, "DEPTH": 1, "SRV_PAR": 1},
      {"NC": 2, "NSV": 1, "DEPTH": 2, "SRV_PAR": 1}, {"NC": 2, "NSV": 1, "DEPTH": 2, "SRV_PAR": 2},
      {"NC": 2, "NSV": 2, "DEPTH": 2, "SRV_PAR": 1}],
     []),
    ("tcp_gateway.toml", "TCP gateway",
     "Modbus/TCP clients through the gateway to scenario B's serial slaves: a present unit, a routed unit "
     "with no slave (0B) and a unit with no route (0A), C x depth x NS",
     {**COMMON, "NSV": "1", "CONFIG": '"B"', "SCRIPTS": '"gateway"'},
     [{"NC": 1, "DEPTH": 1, "NS": 1}, {"NC": 1, "DEPTH": 2, "NS": 1}, {"NC": 2, "DEPTH": 1, "NS": 1},
      {"NC": 1, "DEPTH": 2, "NS": 3}],
     WRITES),
    ("tcp_mixed.toml", "TCP mixed",
     "Modbus/TCP clients using a plain server and the gateway (thesis scenario A's two slaves) with "
     "pipelining, a slow server whose replies come after the client's time-out, and connections closed "
     "and reopened",
     {**COMMON, "SCRIPTS": '"mixed"', "NSV": "1"},
     [{"NC": 1, "DEPTH": 2, "TSRV": "[1, 4000]", "NCLOSE": 0},
      {"NC": 1, "DEPTH": 2, "TSRV": "[1]", "NCLOSE": 1},
      {"NC": 2, "DEPTH": 1, "TSRV": "[1]", "NCLOSE": 0}],
     WRITES),
]

#: (mutant, what the bug is, set, the properties it breaks: the first is the one written to catch it)
ONE = {**COMMON, "NC": "1", "NSV": "1"}
MUTANTS = [
    ("tcp-tid-reuse", "the client numbers a request by its count of outstanding requests plus one, so an id "
     "still outstanding is reused once an earlier request is answered",
     {**ONE, "DEPTH": "2", "SCRIPT": "[(AnySrv, 255, 3, 1), (AnySrv, 255, 3, 1), (AnySrv, 255, 3, 1)]"},
     ["tid-unique", "no-duplicate", "done", "eventually", "eventually-ltl", "all-answered"]),
    ("tcp-wrong-client", "the server sends a response on another client's connection to it",
     {**COMMON, "NC": "2", "NSV": "1", "DEPTH": "1", "SCRIPT": "[(AnySrv, 255, 3, 1)]"},
     ["tid-connection", "match", "no-duplicate", "no-loss"]),
    ("tcp-fifo-match", "the client takes a response as the answer to its oldest outstanding request on the "
     "connection (in order), not by transaction id",
     {**ONE, "DEPTH": "2", "SRV_PAR": "2", "TSRV": "[1, 5]", "SCRIPT": "[(AnySrv, 255, 3, 1), (AnySrv, 255, 6, 1)]"},
     ["match"]),
    ("tcp-depth-off-by-one", "the client checks its limit of outstanding requests with <= instead of <",
     {**ONE, "DEPTH": "1", "SCRIPT": SRV_SCRIPT}, ["depth"]),
    ("tcp-timer-not-cancelled", "the client's time-out of an answered request still fires and reports a "
     "time-out", {**ONE, "DEPTH": "1", "SCRIPT": "[(AnySrv, 255, 3, 1)]"}, ["one-outcome", "done", "eventually-ltl"]),
    ("tcp-server-drops-when-busy", "a server that processes one request at a time drops a request that "
     "arrives while it is busy (as a serial slave does) instead of leaving it in the connection",
     {**ONE, "DEPTH": "2", "SRV_PAR": "1", "SCRIPT": SRV_SCRIPT}, ["no-loss", "all-answered"]),
    ("tcp-duplicate-response", "the server sends every response twice",
     {**ONE, "DEPTH": "1", "SCRIPT": "[(AnySrv, 255, 3, 1)]"}, ["no-duplicate"]),
    ("tcp-mbap-length", "the server's MBAP length field leaves out the unit id",
     {**ONE, "DEPTH": "1", "SCRIPT": "[(AnySrv, 255, 3, 1)]"}, ["mbap"]),
    ("tcp-reopen-same-channel", "the server's TCP stack finds a connection by client and server only, so a "
     "response to a request of a closed connection arrives on the reopened one",
     {**ONE, "DEPTH": "1", "NCLOSE": "1", "SCRIPT": "[(AnySrv, 255, 3, 1), (AnySrv, 255, 3, 1)]"},
     ["tid-connection"]),
    ("tcp-gw-pipeline", "the gateway sends the next queued request onto the serial line without waiting for "
     "the reply to the one before",
     {**ONE, "DEPTH": "2", "SCRIPT": "[(ToGw, 3, 3, 1), (ToGw, 5, 3, 6)]"},
     ["gw-one", "gw-line", "gw-codes", "no-loss", "done"]),
    ("tcp-gw-no-0B", "the gateway drops a request whose target never responds (no exception 0B)",
     {**ONE, "DEPTH": "1", "SCRIPT": "[(ToGw, 6, 3, 1)]"}, ["no-loss", "all-answered"]),
    ("tcp-gw-0B-early", "the gateway answers 0B at the first serial time-out, without its retries",
     {**ONE, "DEPTH": "1", "SCRIPT": "[(ToGw, 6, 3, 1)]"}, ["gw-codes"]),
    ("tcp-gw-no-0A", "the gateway has no routing check: a unit id with no path goes onto the serial line "
     "(and comes back as 0B, not 0A)",
     {**ONE, "DEPTH": "1", "SCRIPT": "[(ToGw, 200, 3, 1)]"}, ["gw-codes"]),
]


def _lit(text: str) -> str:
    return "'''" + text + "'''" if ("\n" in text or '"' in text or "\\" in text) else '"' + text + '"'


def _value(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    return _lit(str(v))


def _properties(skip: list[str], violated: list[str]) -> str:
    out = []
    for key, name, kind, fields in PROPERTIES:
        if key in skip:
            continue
        out.append("[[property]]")
        out.append(f"name = {_lit(name)}")
        out.append(f'kind = "{kind}"')
        for k, v in fields.items():
            out.append(f"{k} = {_value(v)}")
        if key in violated:
            out.append('expect = "violated"  # the bug of this mutant must break it')
        out.append("")
    return "\n".join(out)


HEADER = ("# {what}: written by `python bench/modbus_tcp.py --write-specs` (do not edit by hand).\n"
          "# The choices where the seed and MODBUS.md are silent are in models/modbus/modbus_tcp.cpnet and\n"
          "# docs/modbus_tcp.md; here: no late serial slave (LATE = []), no CRC fault, serial processing 1 ms.\n")


def scenario_text(name, description, sets, rows, skip, model="../../models/modbus/modbus_tcp.cpnet",
                  violated=(), what=None, explore=None) -> str:
    lines = [HEADER.format(what=what or name), f"name = {_lit(name)}", f'model = "{model}"',
             f"description = {_lit(description)}", "", "[set]"]
    lines += [f"{k} = {_value(v)}" for k, v in sets.items()]
    lines += ["", "[explore]", "time_condensation = true", "max_seconds = 300"]
    for k, v in (explore or {}).items():
        lines.append(f"{k} = {_value(v)}")
    lines.append("")
    for row in rows:
        lines.append("[[parameters]]")
        lines += [f"{k} = {_value(v)}" for k, v in row.items()]
        lines.append("")
    lines.append(_properties(skip, list(violated)))
    return "\n".join(lines).rstrip() + "\n"


def write_specs() -> None:
    for fname, name, description, sets, rows, skip in SCENARIOS:
        with open(os.path.join(SPECS, fname), "w") as fh:
            fh.write(scenario_text(name, description, sets, rows, skip))
    for mutant, bug, sets, violated in MUTANTS:
        text = scenario_text(f"TCP mutant {mutant}", f"Bug: {bug}. The TCP property set; the bug breaks the "
                             "properties marked expect = violated.", {**sets, "TMUTANT": f'"{mutant}"'}, [],
                             WRITES, model="../../../models/modbus/modbus_tcp.cpnet", violated=violated)
        with open(os.path.join(SPECS, "mutants", mutant.replace("-", "_") + ".toml"), "w") as fh:
            fh.write(text)


# ---------------------------------------------------------------------------------------------- scale
def _explore(sets: dict, extra: list[str], budget: float) -> dict | None:
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "r.json")
        cmd = [sys.executable, "-m", "cpn", "explore", MODEL, "--quiet", "--json", out, "--max-seconds", str(budget)]
        for k, v in sets.items():
            cmd += ["--set", f"{k}={v}"]
        proc = subprocess.run(cmd + extra, capture_output=True, text=True)
        if not os.path.exists(out):
            print(proc.stderr, file=sys.stderr)
            return None
        with open(out) as fh:
            data = json.load(fh)
    ss = data["statespace"]
    red = data.get("reduction") or {}
    return {"states": ss["states"], "complete": ss["complete"], "seconds": ss["seconds"],
            "full_states": red.get("full_states"), "peak": ss.get("peak_states")}


#: a progress measure for the sweep-line under time condensation: requests sent, responses received,
#: outcomes and serial frames only grow
PROGRESS = ("size (sum Client'Sent) + size (sum Client'Got) + size (sum Client'Done) + "
            "ms_to_col (Gateway'SerialId 1)")
SCALE_SRV = [(1, 1, 1), (2, 1, 2), (2, 2, 2), (3, 1, 2), (3, 2, 2), (4, 1, 2), (3, 3, 2), (4, 2, 2), (5, 1, 2)]
SCALE_GW = [(1, 1, 1), (1, 2, 3), (2, 1, 1), (2, 2, 3), (3, 1, 1), (3, 2, 3), (4, 2, 3), (5, 2, 3)]


def scale(budget: float, rows: str) -> None:
    print("| family | C | S | depth | NS | full | symmetry: orbits (full graph) | sweep-line, clock: states (peak) "
          "| sweep-line, progress: states (peak) |")
    print("|---|---|---|---|---|---|---|---|---|")
    srv = SCALE_SRV if rows == "all" else [] if rows == "gateway" else SCALE_SRV[:4]
    gw = SCALE_GW if rows in ("all", "gateway") else SCALE_GW[:3]
    configs = [("servers", {**COMMON, "NC": c, "NSV": s, "DEPTH": d}, (c, s, d, "-")) for c, s, d in srv]
    configs += [("gateway", {**COMMON, "CONFIG": '"B"', "SCRIPTS": '"gateway"', "NC": c, "DEPTH": d, "NS": ns},
                 (c, 1, d, ns)) for c, d, ns in gw]

    def cell(r, text):
        if r is None:
            return "error"
        return text + (f" in {r['seconds']:.1f} s" if r["complete"] else f" (stopped at {budget:.0f} s)")

    for family, sets, (c, s, d, ns) in configs:
        full = _explore(sets, ["--time-condensation"], budget)
        sym = _explore(sets, ["--time-condensation", "--reduction", "symmetry"], budget)
        clock = _explore(sets, ["--sweep-line"], budget)
        prog = _explore(sets, ["--time-condensation", "--sweep-line", "--progress", PROGRESS], budget)
        cells = [cell(full, f"{full['states']:,}") if full else "error",
                 cell(sym, f"{sym['states']:,} ({sym['full_states'] or 0:,})") if sym else "error",
                 cell(clock, f"{clock['states']:,} ({clock['peak'] or 0:,})") if clock else "error",
                 cell(prog, f"{prog['states']:,} ({prog['peak'] or 0:,})") if prog else "error"]
        print(f"| {family} | {c} | {s} | {d} | {ns} | " + " | ".join(cells) + " |", flush=True)


def mutants() -> None:
    """Each mutant file checked in this process: the properties it breaks, with the length of the shortest
    trace among them (none for a `reachable` property without a witness)."""
    sys.path.insert(0, ROOT)
    from cpn.checks.verdict import Status
    from cpn.gate.run import run_scenario
    from cpn.gate.scenario import load_scenario

    short = {key: name.split(":")[0] for key, name, _, _ in PROPERTIES}
    print("| mutant | bug | configuration | properties violated (shortest trace) | states |")
    print("|---|---|---|---|---|")
    for mutant, bug, sets, broken in MUTANTS:
        scenario = load_scenario(os.path.join(SPECS, "mutants", mutant.replace("-", "_") + ".toml"))
        result = run_scenario(scenario, scenario.runs[0])
        names = {name: key for key, name, _, _ in PROPERTIES}
        violated = [r for r in result.results if r.verdict.status is Status.VIOLATED]
        keys = [names[r.spec.name] for r in violated]
        lengths = [len(r.verdict.evidence.path) - 1 for r in violated if r.verdict.evidence is not None]
        config = ", ".join(f"{k} {v}" for k, v in sets.items() if k in ("NC", "NSV", "DEPTH", "SRV_PAR", "NCLOSE"))
        # the property written to catch the bug first, in bold
        keys.sort(key=lambda k: k != broken[0])
        cells = ", ".join(f"**{short[k]} ({k})**" if k == broken[0] else f"{short[k]} ({k})" for k in keys)
        print(f"| {mutant} | {bug} | {config} | {cells} ({min(lengths) if lengths else '-'}) | "
              f"{result.exploration.graph.n_states:,} |", flush=True)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--write-specs", action="store_true")
    ap.add_argument("--scale", action="store_true")
    ap.add_argument("--mutants", action="store_true")
    ap.add_argument("--budget", type=float, default=120)
    ap.add_argument("--rows", choices=["small", "all", "gateway"], default="small")
    args = ap.parse_args()
    if args.write_specs:
        write_specs()
    if args.mutants:
        mutants()
    if args.scale:
        scale(args.budget, args.rows)


if __name__ == "__main__":
    main()
