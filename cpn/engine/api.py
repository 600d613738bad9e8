"""Conveniences shared by both engines, built on `successors` (docs/internals.md)."""

from __future__ import annotations


class EngineAPI:
    """Mixed into the compiled engine and the reference interpreter."""

    def enabled(self, state) -> list:
        """The enabled binding elements of `state`, in the engine's fixed order."""
        return [self.binding_element(be) for be, _ in self.successors(state)]

    def fire(self, state, binding_element):
        """The marking reached by firing one enabled binding element.

        `binding_element` is a binding element id, a `BindingElement`, or its text
        (``"Top'Send 1: {a=1, f=3}"``). Raises ValueError if it is not enabled in `state`.
        """
        for be, succ in self.successors(state):
            if be == binding_element or self.format_binding_element(be) == binding_element \
                    or self.binding_element(be) == binding_element:
                return succ
        raise ValueError(f"{binding_element!r} is not enabled in this state")
