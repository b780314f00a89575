"""Why a load path stopped: the material's own instability told apart from a numerical failure.

A Newton failure deep in a solve reads "did not converge ... To try: a finer mesh". When the
tube's largest principal stretch at the last converged state has reached the stretch from
which the material's parameters are Drucker-unstable (``dP/dl <= 0``; a soft Ogden-1 with
``alpha < 1`` in tension), no mesh or step cures it: :func:`explain_failure` then turns the
error into a :class:`~exofric.errors.MaterialInstabilityError` naming the model, its
parameters, the unstable stretch and the stretch reached (issue 38).
"""

from __future__ import annotations

from typing import Any

from exofric.errors import ConvergenceError, MaterialInstabilityError

__all__ = ["explain_failure"]


def explain_failure(problem: Any, u: Any, exc: ConvergenceError) -> ConvergenceError:
    """``exc``, or a :class:`MaterialInstabilityError` if the material explains the failure.

    Parameters
    ----------
    problem : object
        The FE problem that failed; its ``body`` (a hyperelastic body with ``max_stretch(u)``
        and ``model.source``) is read if it has one.
    u : ndarray
        The last converged displacements (mm).
    exc : ConvergenceError
        The failure as the load stepping words it (``... . To try: ...``).

    Returns
    -------
    ConvergenceError
        ``exc`` unchanged, or the stability error (same ``reached``).

    Examples
    --------
    >>> e = ConvergenceError("Newton failed", reached=0.5)
    >>> explain_failure(object(), None, e) is e      # no body: nothing to explain
    True
    """
    from exofric.material import HyperelasticModel, MooneyRivlin

    body = getattr(problem, "body", None)
    source = getattr(getattr(body, "model", None), "source", None)
    model = source.to_model() if isinstance(source, MooneyRivlin) else source
    if body is None or u is None or not isinstance(model, HyperelasticModel):
        return exc
    stretch = float(body.max_stretch(u))
    found = model.section_instability(stretch)
    if found is None:
        return exc
    why, onset = found
    head = str(exc).split(". To try:")[0]
    return MaterialInstabilityError(
        f"{head}, {why}. To try: parameters stable to a larger stretch "
        "(HyperelasticModel.stability) or lower loads",
        reached=exc.reached, stretch=stretch, onset=onset)
