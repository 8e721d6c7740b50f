# SPDX-License-Identifier: GPL-3.0-or-later
"""Opening a haptic device on a worker thread, so that the thread asking (FreeCAD's GUI
thread) never waits on USB.

``_core.open_device(path)`` exchanges feature reports with a HID device; a device that
does not answer blocks each exchange in the kernel for up to 5 s (usbhid's control
timeout), so an open can take some 10 s. The binding releases the GIL meanwhile, so a
Python thread can do it while the Qt event loop runs:

    opening = DeviceOpening("/dev/hidraw3")   # returns at once: the worker opens
    opening.poll()        # None while it opens; then the device (handed over once), or
                          # raises the device layer's error (_core.DeviceError, a RuntimeError)
    opening.abandon()     # the caller gave up: a device opened before or after is released

A device nobody takes (abandoned) is dropped, so its destructor closes it (for a HID
device: its session ends and both hidapi handles close) on the thread that drops it last.
Until an abandoned open is over, the same device is not to be opened again
(``still_giving_up``): the late open's exchanges, and the end of its session when it is
dropped, would reach the device in the middle of the new session's.

No GUI, no FreeCAD: tested headless (tests/plugin/hapticad/test_device_opening.py).
Thread safety: poll(), abandon(), still_opening and wait() are for one owner thread;
the worker only runs the open and hands over its outcome under a lock.
"""
import threading

from . import _core

# path -> the abandoned openings of it whose worker still runs
_GIVING_UP = {}
_GIVING_UP_LOCK = threading.Lock()


def still_giving_up(path):
    """True while an open of ``path`` that was abandoned has not ended (the device is
    still answering it, or its late session is being ended): open it again only after."""
    with _GIVING_UP_LOCK:
        return bool(_GIVING_UP.get(path))


class DeviceOpening:
    """One device being opened, by ``open_device(path)`` (``_core.open_device`` unless
    given: any callable that opens and returns the device or raises) on a daemon
    thread started here."""

    def __init__(self, path, open_device=None):
        self.path = path
        self._open = open_device or _core.open_device
        self._lock = threading.Lock()
        self._finished = False  # the worker is done (the outcome below, unless abandoned)
        self._abandoned = False
        self._handed_over = False
        self._device = None
        self._error = None
        self._thread = threading.Thread(target=self._run, name=f"HaptiCAD open {path}", daemon=True)
        self._thread.start()

    def _run(self):
        device = error = None
        try:
            device = self._open(self.path)
        except Exception as exc:  # noqa: BLE001 (handed to the owner, who raises it in poll())
            error = exc
        finally:  # whatever ends the open (a SystemExit too), it is over: never "opening" for good
            if device is None and error is None:
                error = RuntimeError(f"opening {self.path} was interrupted")
            with self._lock:
                self._finished = True
                if not self._abandoned:
                    self._device, self._error = device, error
                    device = None
            # abandoned meanwhile: nobody will take it. Dropped here, its destructor closes it
            del device
            with _GIVING_UP_LOCK:
                _GIVING_UP.get(self.path, set()).discard(self)

    @property
    def still_opening(self):
        """True until the worker has an outcome (and it is not abandoned)."""
        with self._lock:
            return not self._finished and not self._abandoned

    def poll(self):
        """Never blocks. None while the device is still opening; then the opened device,
        handed over to the caller (who owns it from then on), or raises what the open
        raised (_core.DeviceError, a RuntimeError, with the device layer's message).
        Precondition: not abandoned and not handed over already (RuntimeError)."""
        with self._lock:
            if self._abandoned or self._handed_over:
                raise RuntimeError(f"the opening of {self.path} was "
                                   + ("abandoned" if self._abandoned else "handed over already"))
            if not self._finished:
                return None
            if self._error is not None:
                raise self._error
            self._handed_over = True
            device, self._device = self._device, None
            return device

    def abandon(self):
        """The owner gives up (Stop, the panel closed): a device opened already and not
        taken is dropped now, one the worker opens later is dropped by the worker (until
        then ``still_giving_up`` says so). Does not wait for the worker. A device handed
        over by poll() stays the owner's."""
        with self._lock:
            self._abandoned = True
            device, self._device = self._device, None
            self._error = None
            if not self._finished:  # the worker takes itself off when it is done
                with _GIVING_UP_LOCK:
                    _GIVING_UP.setdefault(self.path, set()).add(self)
        del device  # outside the lock: its destructor may take a moment (its writer thread)

    def wait(self, timeout_s=None):
        """Blocks until the worker is done (tests, a command line), at most ``timeout_s``;
        True when it is. Not for the GUI thread."""
        self._thread.join(timeout_s)
        return not self._thread.is_alive()
