"""Terms of PNML symmetric nets (inscriptions, initial markings, conditions) translated into CPN ML.

A mixin of `cpn.io.pnml`'s translator: one method `t_<operator>` per PNML operator, each returning a
`_Term`. Unknown operators are reported (E0502) and replaced by a placeholder so that one run finds
them all. Imports the stdlib and `cpn.io.pnml._*` only.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from cpn.io.pnml._sorts import Sort, int_text
from cpn.io.pnml._xml import Element


@dataclass
class _Term:
    """A translated PNML term: CPN ML text, whether it is a multiset, and its sort when known.

    `expansion` lists the (multiplicity, value text) pairs of a multiset made of `all` expansions,
    partition elements and sums of single values, so that `numberof` and `tuple` can expand them further."""

    text: str
    is_ms: bool = False
    sort: Sort | None = None
    atomic: bool = True
    expansion: list[tuple[int, str]] | Callable[[], list[tuple[int, str]]] | None = None

    def items(self) -> list[tuple[int, str]]:
        """The expansion, computed on first use (a product sort's `all` can be large and is rarely
        expanded)."""
        if callable(self.expansion):
            self.expansion = self.expansion()
        return self.expansion

    def paren(self) -> str:
        return self.text if self.atomic else f"({self.text})"

    def as_ms(self) -> str:
        return self.text if self.is_ms else f"1`{self.paren()}"


# the largest factor by which a computed multiset is repeated with ++ (scalarproduct, numberof)
MAX_REPEAT: int = 16


class TermTranslator:
    """The term half of the PNML translator; the host provides error(), sort_of(), resolve_sort(),
    and the tables vars, consts, sorts, sort_els and names."""

    def term(self, el: Element, where: str, expect: Sort | None = None) -> _Term:
        """Translate a PNML term; unsupported operators are reported and replaced by a placeholder."""
        handler = getattr(self, "t_" + el.tag, None)
        if handler is None:
            self.error(el, f"unsupported PNML operator '{el.tag}' in {where}",
                       hint="docs/pnml.md lists the operators that cpn-verify translates.")
            return _Term("()")
        return handler(el, where, expect)

    def subterms(self, el: Element, where: str, expect: Sort | None = None) -> list[_Term]:
        out = []
        for s in el.elements():
            inner = s.elements() if s.tag == "subterm" else [s]
            if s.tag not in ("subterm",) and s.tag in ("usersort",):
                continue
            if inner:
                out.append(self.term(inner[0], where, expect))
        return out

    def _arity(self, el: Element, terms: list[_Term], n: int, where: str) -> bool:
        if len(terms) != n:
            self.error(el, f"'{el.tag}' in {where} has {len(terms)} operands, expected {n}", code="E0501")
            return False
        return True

    def t_variable(self, el, where, expect):
        ref = el.get("refvariable", "")
        if ref not in self.vars:
            self.error(el, f"unknown variable '{ref}' in {where}", code="E0501")
            return _Term("()")
        ident, sort = self.vars[ref]
        return _Term(ident, sort=sort)

    def t_useroperator(self, el, where, expect):
        ref = el.get("declaration", "")
        if ref not in self.consts and ref in self.sorts and self.sorts[ref].kind == "dot":
            return _Term("()", sort=self.sorts[ref])  # TAPAAL names the dot constant by its sort
        if ref not in self.consts:
            self.error(el, f"unknown constant '{ref}' in {where}",
                       hint="Only constants (feconstant, partitionelement) can be used as user operators.",
                       code="E0501")
            return _Term("()")
        ident, sort = self.consts[ref]
        if sort.base is not None and expect is sort.base:
            # A partition element where a value of the partitioned sort is expected: the element is
            # the set of constants it lists (ISO/IEC 15909-2, partitions), so it stands for their sum.
            members = [c for c in sort.base.consts if sort.element_of[c] == ident]
            exp = [(1, c) for c in members]
            return _Term(_ms_text(exp), is_ms=True, sort=sort.base, atomic=False, expansion=exp)
        return _Term(ident, sort=sort)

    def t_dotconstant(self, el, where, expect):
        return _Term("()", sort=self.sort_of(Element("dot", {}, el.line, el.col), el))

    def t_booleanconstant(self, el, where, expect):
        v = (el.get("value") or "").lower()
        if v not in ("true", "false"):
            self.error(el, f"booleanconstant in {where} has value '{v}'", code="E0501")
        return _Term("true" if v == "true" else "false", sort=self.sort_of(Element("bool", {}, el.line, el.col), el))

    def t_numberconstant(self, el, where, expect):
        try:
            n = int(el.get("value", ""))
        except ValueError:
            self.error(el, f"numberconstant in {where} has no integer value", code="E0501")
            n = 0
        return _Term(int_text(n), atomic=n >= 0)

    def t_finiteintrangeconstant(self, el, where, expect):
        term = self.t_numberconstant(el, where, expect)
        r = el.find("finiteintrange")
        if expect is not None and expect.kind == "range":
            term.sort = expect
        elif r is not None:
            term.sort = self.sort_of(r, el)
        return term

    def t_all(self, el, where, expect):
        sort_el = next(iter(el.elements()), None)
        sort = self.sort_of(sort_el, el) if sort_el is not None else None
        if sort is None:
            return _Term("empty", is_ms=True)
        return _Term(f"{sort.name}.all()", is_ms=True, sort=sort, expansion=sort_values(sort))

    def t_numberof(self, el, where, expect):
        terms = self.subterms(el, where, expect)
        if len(terms) == 1 and not terms[0].text.lstrip("~").isdigit():
            # a numberof with only its term (seen in some contest files) is one of it
            terms = [_Term("1"), terms[0]]
        if not self._arity(el, terms, 2, where):
            return _Term("empty", is_ms=True)
        count, what = terms
        try:
            n = int(count.text.replace("~", "-"))
        except ValueError:
            self.error(el, f"the multiplicity of 'numberof' in {where} is not a constant", code="E0502")
            return _Term("empty", is_ms=True)
        if n < 0:
            self.error(el, f"the multiplicity of 'numberof' in {where} is negative", code="E0501")
            return _Term("empty", is_ms=True)
        if n == 0:
            return _Term("empty", is_ms=True, atomic=True)
        if not what.is_ms:
            return _Term(f"{n}`{what.paren()}", is_ms=True, sort=what.sort, atomic=False,
                         expansion=[(n, what.paren())])
        return self._scale(el, where, n, what)

    def _scale(self, el, where, n: int, what: _Term) -> _Term:
        """n times the multiset `what`: its elements' multiplicities times n when they are known, else
        `what` added n times (CPN ML has no scalar product of multisets)."""
        if n == 1:
            return what
        if what.expansion is not None:
            exp = [(n * k, v) for k, v in what.items()]
            return _Term(_ms_text(exp), is_ms=True, sort=what.sort, atomic=False, expansion=exp)
        if n > MAX_REPEAT:
            self.error(el, f"'{el.tag}' in {where} multiplies a computed multiset by {n}",
                       hint=f"Only multiplicities up to {MAX_REPEAT} of a multiset that is not made of constants "
                            "and 'all' can be translated.")
            return what
        text = what.text if what.atomic else f"({what.text})"
        return _Term(" ++ ".join([text] * n), is_ms=True, sort=what.sort, atomic=False)

    def t_scalarproduct(self, el, where, expect):
        terms = self.subterms(el, where, expect)
        if not self._arity(el, terms, 2, where):
            return _Term("empty", is_ms=True)
        count, what = terms
        try:
            n = int(count.text.replace("~", "-"))
        except ValueError:
            self.error(el, f"the factor of 'scalarproduct' in {where} is not a constant")
            return _Term("empty", is_ms=True)
        if n <= 0:
            return _Term("empty", is_ms=True)
        return self._scale(el, where, n, what if what.is_ms else _Term(what.as_ms(), is_ms=True, sort=what.sort,
                                                                        atomic=False, expansion=[(1, what.paren())]))

    def t_empty(self, el, where, expect):
        return _Term("empty", is_ms=True, expansion=[])

    def t_tuple(self, el, where, expect):
        parts = [s for s in el.elements() if s.tag != "subterm" or s.elements()]
        if len(parts) == 1 and (expect is None or expect.kind != "product"):
            # GreatSPN wraps every term of a sort that is not a product in a one-component tuple
            # (`<tuple><subterm><variable/></subterm></tuple>`); the contest's tools read the term itself.
            inner = parts[0].elements()[0] if parts[0].tag == "subterm" else parts[0]
            return self.term(inner, where, expect)
        comp = expect.parts if expect is not None and expect.kind == "product" else []
        terms = []
        for i, s in enumerate(el.elements()):
            inner = s.elements() if s.tag == "subterm" else [s]
            if inner:
                terms.append(self.term(inner[0], where, comp[i] if i < len(comp) else None))
        if len(terms) < 2:
            self.error(el, f"a tuple in {where} has {len(terms)} component(s)", code="E0501")
            return terms[0] if terms else _Term("()")
        if not any(t.is_ms for t in terms):
            return _Term("(" + ", ".join(t.text for t in terms) + ")", sort=expect)
        # a tuple with 'all' components is the multiset of every tuple it stands for
        choices: list[list[tuple[int, str]]] = []
        for t in terms:
            if t.is_ms:
                if t.expansion is None:
                    self.error(el, f"a tuple in {where} has a multiset component that is not made of "
                                   "'all', constants, variables and partition elements")
                    return _Term("empty", is_ms=True)
                choices.append(t.items())
            else:
                choices.append([(1, t.text)])
        exp: list[tuple[int, str]] = [(1, "")]
        for ch in choices:
            exp = [(k1 * k2, f"{v1}, {v2}" if v1 else v2) for k1, v1 in exp for k2, v2 in ch]
        exp = [(k, f"({v})") for k, v in exp]
        return _Term(_ms_text(exp), is_ms=True, sort=expect, atomic=False, expansion=exp)

    def t_add(self, el, where, expect):
        terms = self.subterms(el, where, expect)
        if not terms:
            return _Term("empty", is_ms=True)
        if len(terms) == 1:
            return terms[0]
        exp = None
        if all(t.expansion is not None or not t.is_ms for t in terms):
            # a sum of constants, variables and 'all's is known element by element, so that a tuple
            # can have it as a component (`<pr1, tx2, bs1+bs2>`, VehicularWifi-COL)
            def exp(terms=terms):
                return [kv for t in terms for kv in (t.items() if t.is_ms else [(1, t.paren())])]
        return _Term(" ++ ".join(t.as_ms() for t in terms), is_ms=True, sort=expect, atomic=False, expansion=exp)

    def t_subtract(self, el, where, expect):
        terms = self.subterms(el, where, expect)
        if len(terms) < 2:
            self._arity(el, terms, 2, where)
            return terms[0] if terms else _Term("empty", is_ms=True)
        parts = [terms[0].as_ms()]
        parts += [f"({t.as_ms()})" if (" ++ " in t.text or " -- " in t.text) else t.as_ms() for t in terms[1:]]
        text = " -- ".join(parts)
        return _Term(text, is_ms=True, sort=expect, atomic=False)

    def _step(self, el, where, op):
        terms = self.subterms(el, where)
        if not self._arity(el, terms, 1, where):
            return _Term("()")
        t = terms[0]
        if t.sort is None or t.sort.kind not in ("enum", "range", "bool"):
            self.error(el, f"'{el.tag}' in {where} is applied to a value whose sort is not an enumeration or range")
            return t
        text = t.sort.succ(t.paren()) if op == "succ" else t.sort.pred(t.paren())
        return _Term(text, sort=t.sort, atomic=text.startswith("("))

    def t_successor(self, el, where, expect):
        return self._step(el, where, "succ")

    def t_predecessor(self, el, where, expect):
        return self._step(el, where, "pred")

    def _compare(self, el, where, op, ordered):
        terms = self.subterms(el, where)
        if not self._arity(el, terms, 2, where):
            return _Term("false")
        a, b = terms
        if not ordered and a.sort is not None and b.sort is not None and a.sort is not b.sort:
            # a value of a partitioned sort against a partition element: whether the value lies in it
            if b.sort.base is a.sort:
                a = _Term(f"{b.sort.helper('of', self.names)} {a.paren()}", sort=b.sort, atomic=False)
            elif a.sort.base is b.sort:
                b = _Term(f"{a.sort.helper('of', self.names)} {b.paren()}", sort=a.sort, atomic=False)
        sort = a.sort or b.sort
        if ordered and sort is not None and sort.kind in ("enum", "bool"):
            return _Term(f"{sort.ord(a.paren())} {op} {sort.ord(b.paren())}", atomic=False)
        if ordered and (sort is None or sort.kind not in ("range",)):
            if sort is None and not (a.text.lstrip("~").isdigit() and b.text.lstrip("~").isdigit()):
                self.error(el, f"'{el.tag}' in {where} compares values whose sort is unknown")
            elif sort is not None:
                self.error(el, f"'{el.tag}' in {where} compares values of sort '{sort.name}', which has no order")
        return _Term(f"{a.paren()} {op} {b.paren()}", atomic=False)

    def t_equality(self, el, where, expect):
        return self._compare(el, where, "=", False)

    def t_inequality(self, el, where, expect):
        return self._compare(el, where, "<>", False)

    def t_lessthan(self, el, where, expect):
        return self._compare(el, where, "<", True)

    def t_lessthanorequal(self, el, where, expect):
        return self._compare(el, where, "<=", True)

    def t_greaterthan(self, el, where, expect):
        return self._compare(el, where, ">", True)

    def t_greaterthanorequal(self, el, where, expect):
        return self._compare(el, where, ">=", True)

    # order of partition elements (ISO 15909-2 'partitions')
    def t_ltp(self, el, where, expect):
        return self._compare(el, where, "<", True)

    def t_gtp(self, el, where, expect):
        return self._compare(el, where, ">", True)

    # integer operators of finite int ranges (ISO 15909-2 'integers')
    t_lt, t_leq, t_gt, t_geq = t_lessthan, t_lessthanorequal, t_greaterthan, t_greaterthanorequal

    def _arith(self, el, where, op):
        terms = self.subterms(el, where)
        if not self._arity(el, terms, 2, where):
            return _Term("0")
        a, b = terms
        return _Term(f"{a.paren()} {op} {b.paren()}", sort=a.sort or b.sort, atomic=False)

    def t_addition(self, el, where, expect):
        return self._arith(el, where, "+")

    def t_subtraction(self, el, where, expect):
        return self._arith(el, where, "-")

    def t_mult(self, el, where, expect):
        return self._arith(el, where, "*")

    def t_div(self, el, where, expect):
        return self._arith(el, where, "div")

    def t_mod(self, el, where, expect):
        return self._arith(el, where, "mod")

    def _logic(self, el, where, op):
        # and/or are associative: nested ones of the same kind become one chain
        flat: list[Element] = []

        def collect(node: Element) -> None:
            for s in node.elements():
                inner = s.elements() if s.tag == "subterm" else [s]
                if inner and inner[0].tag == node.tag:
                    collect(inner[0])
                elif inner:
                    flat.append(inner[0])

        collect(el)
        terms = [self.term(x, where) for x in flat]
        if not terms:
            return _Term("true" if op == "andalso" else "false")
        if len(terms) == 1:
            return terms[0]
        return _Term(f" {op} ".join(t.paren() for t in terms), atomic=False)

    def t_and(self, el, where, expect):
        return self._logic(el, where, "andalso")

    def t_or(self, el, where, expect):
        return self._logic(el, where, "orelse")

    def t_not(self, el, where, expect):
        terms = self.subterms(el, where)
        if not self._arity(el, terms, 1, where):
            return _Term("false")
        return _Term(f"not {terms[0].paren()}", atomic=False)

    def t_imply(self, el, where, expect):
        terms = self.subterms(el, where)
        if not self._arity(el, terms, 2, where):
            return _Term("true")
        return _Term(f"not {terms[0].paren()} orelse {terms[1].paren()}", atomic=False)

    def t_partitionelementof(self, el, where, expect):
        ref = el.get("refpartition", "")
        part = self.sorts.get(ref)
        if part is None and ref in self.sort_els:
            part = self.resolve_sort(ref, self.sort_els[ref])
        terms = self.subterms(el, where)
        if part is None or part.base is None:
            self.error(el, f"unknown partition '{ref}' in {where}", code="E0501")
            return _Term("()")
        if not self._arity(el, terms, 1, where):
            return _Term("()")
        return _Term(f"{part.helper('of', self.names)} {terms[0].paren()}", sort=part, atomic=False)



def sort_values(sort: Sort) -> Callable[[], list[tuple[int, str]]]:
    return lambda: [(1, v) for v in sort.values()]


def _ms_text(exp: list[tuple[int, str]]) -> str:
    return " ++ ".join(f"{k}`{v}" for k, v in exp if k) or "empty"
