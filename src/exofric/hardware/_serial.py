"""Serial devices speaking the exofric line protocol (pyserial).

The protocol (``examples/serial-protocol.md``) is ASCII, one line per message, ``\\n``
terminated, host first; every command gets exactly one answer line:

* ``?`` -> ``EXOFRIC-RIG 1 <name> <firmware>`` (handshake; ``1`` is the protocol version);
* ``R`` -> ``D <t_ms> <p_mpa> <f_n>`` (device time in ms of the sample, pressure MPa gauge,
  force N) or ``ERR <text>``;
* ``S <p_mpa>`` -> ``OK`` (pressure set-point in MPa) or ``ERR <text>`` (out of range, not a
  number: refused, nothing changes);
* ``V`` -> ``OK`` (vent: set-point 0 and the exhaust valve open);
* ``W <ms>`` -> ``OK`` (device watchdog: vent when no command arrives for ``ms``; 0 = off)
  or ``ERR <text>``.

A refused ``S`` or ``W`` is a :class:`DeviceError`; ``ERR`` to ``R`` (e.g. ``ERR stale``),
a missing answer and a well-formed ``D`` line with a non-finite value (``nan``) are
:class:`SensorStale`, counted by the control loop's watchdog; an answer that cannot be parsed
(junk on the line) and a port that fails (unplugged) are :class:`DeviceFault`: the loop vents
(on a reopened port when the old one is dead) and stops at once.
"""

from __future__ import annotations

import math
import time
from typing import Any

from exofric import defaults as D
from exofric.hardware._device import (
    DEFAULT_BAUD,
    DEFAULT_CONNECT_TIMEOUT_S,
    DEFAULT_IO_TIMEOUT_S,
    DeviceBase,
    DeviceError,
    DeviceFault,
    DeviceURL,
    Reading,
    SensorStale,
)

__all__ = ["PROTOCOL_VERSION", "DEVICE_WATCHDOG_MS", "SerialDevice"]

#: The line-protocol version this host speaks (the handshake's second word).
PROTOCOL_VERSION = 1
#: Device-side watchdog the host sets at open, in ms: the firmware vents when no command
#: arrives for this long (host crashed or unplugged).
DEVICE_WATCHDOG_MS = D.DEVICE_WATCHDOG_MS
#: Interval in s between handshake attempts while the board boots (Arduinos reset on open).
_HANDSHAKE_RETRY_S = 0.25


class SerialDevice(DeviceBase):
    """A rig on a serial port speaking the exofric line protocol.

    Opening retries the ``?`` handshake for up to 2 s (boards that reset when the port opens),
    checks the protocol version and sets the device watchdog (``W``,
    :data:`DEVICE_WATCHDOG_MS`).

    Parameters
    ----------
    url : DeviceURL
        ``serial:///dev/ttyX?baud=115200&timeout=0.25`` (timeout per answer in s).

    Examples
    --------
    >>> from exofric.hardware import SerialSimDevice, open_device
    >>> with SerialSimDevice() as sim, open_device(sim.url) as dev:
    ...     dev.identity.split()[:2]
    ['EXOFRIC-RIG', '1']
    """

    def __init__(self, url: DeviceURL) -> None:
        self.url = url.text
        self.timeout_s = url.number("timeout", DEFAULT_IO_TIMEOUT_S, 0.001, 60.0, "s")
        self._path = url.path
        self._baud = int(url.number("baud", DEFAULT_BAUD, 50, 4e6, "bit/s"))
        self.port: Any = self._open(DeviceError)
        try:
            self.identity = self._handshake()
            self._command(f"W {DEVICE_WATCHDOG_MS}", expect="OK")
        except DeviceError:
            self.port.close()
            raise

    def _open(self, error: type[DeviceError]) -> Any:
        import serial

        try:
            return serial.Serial(self._path, baudrate=self._baud, timeout=self.timeout_s,
                                 write_timeout=self.timeout_s)
        except (serial.SerialException, OSError, ValueError) as exc:
            why = " ".join(str(exc).split())
            raise error(f"{self.url}: cannot open the port ({why})") from None

    def reconnect(self) -> None:
        """Close the port, reopen it and repeat the handshake (up to 2 s: boards reset).

        Raises
        ------
        DeviceFault
            The port cannot be reopened or the device does not answer the handshake.
        """
        try:
            self.port.close()
        except Exception:  # noqa: BLE001, S110 - the old port is dead anyway
            pass
        self.port = self._open(DeviceFault)
        try:
            self.identity = self._handshake()
        except DeviceError as exc:
            raise DeviceFault(str(exc)) from None

    def describe(self) -> str:
        """The URL and the firmware's handshake line."""
        return f"{self.url} ({self.identity})"

    def _handshake(self) -> str:
        end = time.monotonic() + DEFAULT_CONNECT_TIMEOUT_S
        last = ""
        while True:
            try:
                answer = self._command("?", timeout_s=_HANDSHAKE_RETRY_S)
            except SensorStale as exc:
                answer, last = "", str(exc).split(": ", 1)[-1]
            if answer:
                words = answer.split()
                if words[0] != "EXOFRIC-RIG" or len(words) < 2:
                    raise DeviceError(f"{self.url}: not an exofric rig (answered {answer!r} to "
                                      "'?'; see examples/serial-protocol.md)")
                if words[1] != str(PROTOCOL_VERSION):
                    raise DeviceError(f"{self.url}: protocol version {words[1]!r}, this exofric "
                                      f"speaks {PROTOCOL_VERSION}")
                return answer
            if time.monotonic() >= end:
                more = f" (last: {last!r})" if last else ""
                raise DeviceError(f"{self.url}: no answer to the handshake '?' within "
                                  f"{DEFAULT_CONNECT_TIMEOUT_S:g} s{more}")

    def _command(self, line: str, *, expect: str | None = None,
                 timeout_s: float | None = None) -> str:
        """Send one command line and return its answer line (without the newline)."""
        import serial

        port = self.port
        word = line.split()[0] if line.split() else repr(line)
        try:
            if port.in_waiting:
                port.reset_input_buffer()      # a late answer to an earlier, timed-out command
            port.write(line.encode("ascii") + b"\n")
            if timeout_s is not None:
                port.timeout = timeout_s
            try:
                raw = port.readline()
            finally:
                if timeout_s is not None:
                    port.timeout = self.timeout_s
        except serial.SerialTimeoutException as exc:     # a write that did not drain in time
            raise SensorStale(f"{self.url}: {word!r}: {' '.join(str(exc).split())}") from None
        except (serial.SerialException, OSError) as exc:  # the port is gone (unplugged)
            raise DeviceFault(f"{self.url}: {word!r}: port failed "
                              f"({' '.join(str(exc).split())})") from None
        if not raw.endswith(b"\n"):
            raise SensorStale(f"{self.url}: no answer to {line.split()[0]!r} within "
                              f"{timeout_s or self.timeout_s:g} s")
        answer = raw.decode("ascii", "replace").strip()
        if answer.startswith("ERR"):
            msg = f"{self.url}: {line.split()[0]!r} refused: {answer[3:].strip() or 'ERR'}"
            if line == "R":
                raise SensorStale(msg)
            raise DeviceError(msg)
        if expect is not None and answer != expect:
            raise DeviceFault(f"{self.url}: expected {expect!r} to {line.split()[0]!r}, got "
                              f"{answer!r}")
        return answer

    def read(self) -> Reading:
        """``R`` -> ``D <t_ms> <p_mpa> <f_n>``: pressure (MPa), force (N), device time (ms).

        Returns
        -------
        Reading
            ``sample_id`` is the device's ``t_ms``.

        Raises
        ------
        SensorStale
            No answer within the timeout, ``ERR``, or a non-finite value (``nan``, ``inf``).
        DeviceFault
            A malformed answer (junk on the line) or a failed port.
        """
        answer = self._command("R")
        words = answer.split()
        try:
            if len(words) != 4 or words[0] != "D":
                raise ValueError
            t_ms, p, f = int(words[1]), float(words[2]), float(words[3])
        except ValueError:
            raise DeviceFault(f"{self.url}: malformed answer to 'R': {answer[:60]!r} (expected "
                              "'D <t_ms> <p_mpa> <f_n>')") from None
        if not (math.isfinite(p) and math.isfinite(f)):
            raise SensorStale(f"{self.url}: 'R' reads pressure {p} MPa, force {f} N "
                              "(no valid value)")
        return Reading(p, f, t_ms)

    def write_setpoint_mpa(self, pressure_mpa: float) -> None:
        """``S <p_mpa>`` -> ``OK``.

        Parameters
        ----------
        pressure_mpa : float
            Set-point in MPa (>= 0), sent with 5 decimals.
        """
        p = self._check_setpoint(pressure_mpa)
        self._command(f"S {p:.5f}", expect="OK")

    def vent(self) -> None:
        """``V`` -> ``OK``."""
        self._command("V", expect="OK")

    def close(self) -> None:
        """Close the port."""
        self.port.close()
