"""What a pickled Surface or Fit is rebuilt by (their __reduce__ names these functions).

Plain Python functions, so pickle stores them by name; the compiled reconstructors check the
state and raise sfit.Error for anything that is not a state sfit wrote."""

from . import _sfit


def surface_from_state(state):
    """The Surface whose __getstate__() is `state` (its JSON text)."""
    return _sfit._surface_from_state(state)


def fit_from_state(state):
    """The Fit whose __reduce__() state is `state`."""
    return _sfit._fit_from_state(state)
