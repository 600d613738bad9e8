"""The flattened net: place and transition instances, as CPN Tools names them."""

from cpn.net.model import ArcInstance, Net, PlaceInstance, TransitionInstance

__all__ = ["ArcInstance", "Net", "PlaceInstance", "TransitionInstance"]
