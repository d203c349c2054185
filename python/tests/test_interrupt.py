"""Ctrl-C: a SIGINT during a long computation raises KeyboardInterrupt in
the caller; the computation is cancelled (ScopedCancellation) instead of
running to its end, and the module stays usable. The computations below take
far longer than the signal's delay (7 to 12 s at these digits)."""

import os
import signal
import threading
import time

import pytest

import uniparam as up


def interrupted(call, after=0.5):
    """Runs call() with a SIGINT sent to this process after `after` s;
    returns the seconds from the signal to the KeyboardInterrupt."""
    sent = []

    def send():
        sent.append(time.monotonic())
        os.kill(os.getpid(), signal.SIGINT)

    timer = threading.Timer(after, send)
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            call()
    finally:
        timer.cancel()
    assert sent, "the computation ended before the signal"
    return time.monotonic() - sent[0]


@pytest.mark.skipif(threading.current_thread() is not threading.main_thread(), reason="signals need the main thread")
@pytest.mark.parametrize("threads", [1, 2])
def test_sigint_cancels_uniformity(threads):
    late = interrupted(lambda: up.uniformity("(t, t^7 - t^2 + 1/3)", digits=2000, threads=threads))
    assert late < 10
    # still usable, with the same results as before
    assert up.uniformity("(t, t^3)").json == up.uniformity("(t, t^3)").json


@pytest.mark.skipif(threading.current_thread() is not threading.main_thread(), reason="signals need the main thread")
def test_sigint_cancels_radical_pieces():
    # radical's pieces run in parallel loops on pool threads: they inherit the
    # cancellation
    late = interrupted(lambda: up.radical("(t^2, t^5 - t^3 + t/7)", digits=2000, threads=2))
    assert late < 10


def test_gil_released_during_computation():
    # another Python thread runs while a computation runs (here one stopped
    # by its 1 s time budget): it wakes 0.3 s into the call and notes the
    # time, which needs the GIL; held by the call, that note would come only
    # after the call has returned
    started = threading.Event()
    noted = []

    def note():
        started.wait()
        time.sleep(0.3)
        noted.append(time.monotonic())

    t = threading.Thread(target=note)
    t.start()
    try:
        started.set()
        with pytest.raises(up.TimeLimitExceeded):
            up.uniformity("(t, t^7 - t^2 + 1/3)", digits=2000, timeout=1)
        end = time.monotonic()
    finally:
        t.join()
    assert noted and noted[0] < end
