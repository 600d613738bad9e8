"""The expression forms that declare their rules in a module of their own (`cpn.expr.form`).

Importing this package registers every form below; the walkers of the tree import it to look forms up.
A new form is a module here, its line below, and its rule in `cpn/lang/grammar.lark`.
"""

from cpn.expr.form import BY_RULE, FORMS, Form, form_of, register
from cpn.expr.forms import (  # noqa: F401 - each registers its forms
    aggregates,  # (a, b), [a, b], {x = a}
    coercions,  # e : T, and 1`e where a multiset is expected
    conditionals,  # if, case
    exceptions,  # raise, handle
    functions,  # fn, op +, #label
    let,  # let ... in ... end
    negation,  # ~ e
    references,  # !e, e1 := e2
    sequence,  # (e1; e2), e1 before e2
)

__all__ = ["BY_RULE", "FORMS", "Form", "form_of", "register"]
