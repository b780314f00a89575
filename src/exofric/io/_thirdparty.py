"""Log lines of the libraries that read files for exofric, turned into exofric's own warnings.

npTDMS logs what it finds odd in a file (a truncated last segment, a data size that is not a
whole number of chunks) through :mod:`logging` handlers of its own that write to stderr:
``[nptdms.reader WARNING] Last segment of file has less data than expected...``. Those lines
would reach a user past exofric's one-line messages (issue 38); :func:`library_log_as_warning`
holds them while a file is read and says them once, as one
:class:`~exofric.errors.PlausibilityWarning` naming the file (the CLI prints it as one
``exofric: warning:`` line and lists it in ``--json``).
"""

from __future__ import annotations

import logging
from collections.abc import Iterator
from contextlib import contextmanager

from exofric.errors import warn_implausible

__all__ = ["library_log_as_warning"]

#: Longest quoted library message in the warning (characters).
_MAX_QUOTE = 160


@contextmanager
def library_log_as_warning(library: str, name: str, what: str) -> Iterator[list[str]]:
    """Hold ``library``'s log records (WARNING and above) during the block; warn once after.

    Parameters
    ----------
    library : str
        The library's top-level logger name (``"nptdms"``): it and every logger under it
        that exists when the block starts (import the library first: its modules make their
        loggers at import).
    name : str
        The file being read, as messages name it (``"run3.tdms"``).
    what : str
        What the records mean for the user, opening the warning (``"the TDMS file looks
        truncated or damaged"``).

    Yields
    ------
    list of str
        The messages held so far (one line each).

    Examples
    --------
    >>> import logging, warnings
    >>> log = logging.getLogger("somelib.reader")     # made when the library is imported
    >>> with warnings.catch_warnings(record=True) as w:
    ...     warnings.simplefilter("always")
    ...     with library_log_as_warning("somelib", "a.tdms", "the file looks damaged"):
    ...         log.warning("Last segment is incomplete")
    >>> str(w[0].message)
    'a.tdms: the file looks damaged (somelib: Last segment is incomplete)'
    """
    held: list[str] = []

    def hold(record: logging.LogRecord) -> bool:
        if record.levelno >= logging.WARNING:
            held.append(" ".join(record.getMessage().split()))
        return False        # never passed on to the library's own stderr handler

    loggers = [logging.getLogger(library)] + [
        logging.getLogger(n) for n in list(logging.root.manager.loggerDict)
        if n.startswith(library + ".")]
    for lg in loggers:
        lg.addFilter(hold)
    try:
        yield held
    finally:
        for lg in loggers:
            lg.removeFilter(hold)
    if held:
        first = held[0] if len(held[0]) <= _MAX_QUOTE else held[0][:_MAX_QUOTE - 3] + "..."
        more = f"; {len(held) - 1} more message{'s' * (len(held) > 2)}" if len(held) > 1 else ""
        warn_implausible(f"{name}: {what} ({library}: {first}{more})")
