"""The browser book's egress trap (lite_harness.EgressTrap) counts requests, not sockets.

Chromium, told to send everything non-loopback through a proxy, opens spare connections to it in advance and drops
them unused when idle; under CI's load two lite tests failed on such sockets, recorded as attempts for the host ''.
A socket closed before it sent a byte asks for nothing: it is counted apart (``unused_connections``).  A request
for a host, or a socket silent for the trap's 2 s, is still an attempt; the browser's own background hosts are
told apart from the site's.  No browser needed: plain sockets against the trap.
"""

from __future__ import annotations

import socket
import time

from .lite_harness import EgressTrap


def _send(port: int, data: bytes) -> None:
    with socket.create_connection(("127.0.0.1", port), timeout=5) as s:
        if data:
            s.sendall(data)
            s.recv(1024)  # the trap's 403


def _wait(cond, timeout=10.0):
    t0 = time.monotonic()
    while not cond() and time.monotonic() - t0 < timeout:
        time.sleep(0.02)
    return cond()


def test_the_trap_counts_requests_not_unused_sockets():
    trap = EgressTrap().start()
    try:
        _send(trap.port, b"")  # a preconnected socket dropped unused
        assert _wait(lambda: trap.unused_connections == 1)
        assert trap.attempts == [] and trap.from_the_site() == []
        _send(trap.port, b"CONNECT www.google.com:443 HTTP/1.1\r\nHost: www.google.com:443\r\n\r\n")  # chromium's own
        _send(trap.port, b"GET http://cdn.example.org/font.woff2 HTTP/1.1\r\nHost: cdn.example.org\r\n\r\n")
        _send(trap.port, b"CONNECT fonts.gstatic.com:443 HTTP/1.1\r\n\r\n")
        assert _wait(lambda: len(trap.attempts) == 3), trap.attempts
        assert [trap.host(a) for a in trap.from_the_site()] == ["cdn.example.org", "fonts.gstatic.com"]
        with socket.create_connection(("127.0.0.1", trap.port), timeout=5) as s:  # silent past the trap's 2 s
            assert _wait(lambda: len(trap.attempts) == 4, timeout=6), trap.attempts
            s.close()
        assert trap.attempts[-1] == "(no request line)" and len(trap.from_the_site()) == 3
        assert trap.unused_connections == 1
    finally:
        trap.stop()
