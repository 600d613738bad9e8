"""Small nets with hand-checked state spaces, for the property checks."""

COUNTER = """net C;
colset N = int with 0..3;
var n : N;
place P : N = 1`0;
trans Inc [n < 3];
arc P -> Inc : n;
arc Inc -> P : n + 1;
"""
# states: P=0 -> 1 -> 2 -> 3 (dead); one arc each; Inc is the only transition

LOOP = """net L;
colset U = unit;
place A : U = 1`();
place B : U;
trans Go;
arc A -> Go;
arc Go -> B;
trans Back;
arc B -> Back;
arc Back -> A;
trans Spin;
arc A -> Spin;
arc Spin -> A;
trans Stop;
arc B -> Stop;
"""
# states: 0 = {A}, 1 = {B}, 2 = {} (dead). Arcs: 0 -Go-> 1, 0 -Spin-> 0, 1 -Back-> 0, 1 -Stop-> 2

SLAVES = """net S;
colset U = unit;
colset ID = int with 1..2;
module Slave(me : ID) {
  place Idle : U = 1`();
  place Busy : U;
  trans Start;
  arc Idle -> Start;
  arc Start -> Busy;
  trans Finish;
  arc Busy -> Finish;
  arc Finish -> Idle;
}
instance "Slave 1" = Slave(me = 1);
instance "Slave 2" = Slave(me = 2);
"""
# two independent two-state slaves: 4 states, one SCC


def scenario(tmp_path, model_text: str, body: str, name: str = "s") -> str:
    """Write a model and a scenario that names it; returns the scenario path."""
    model = tmp_path / f"{name}.cpnet"
    model.write_text(model_text, encoding="utf-8")
    spec = tmp_path / f"{name}.toml"
    spec.write_text(f'model = "{name}.cpnet"\n' + body, encoding="utf-8")
    return str(spec)
