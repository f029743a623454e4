"""Where a server listens and how other machines reach it: a free port, the host to put in an address,
and a check that an address can be listened on (one line, before viser tries)."""

from __future__ import annotations

import socket

from apf_viz.core.formats import InputError


def free_port(host: str = "127.0.0.1") -> int:
    """A TCP port nothing listens on now: for servers started side by side (tests, benchmarks, scripts)."""
    with socket.socket() as sock:
        sock.bind((host, 0))
        return sock.getsockname()[1]


def reachable_host(host: str) -> str:
    """The host to put in an address for other machines: ``host`` itself, or for a server listening on
    every interface (0.0.0.0, ::) this machine's address on its outward network (no packet is sent)."""
    if host not in ("0.0.0.0", "::", ""):
        return host
    try:
        with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as probe:
            probe.connect(("192.0.2.1", 9))  # TEST-NET-1: routes like the internet, never answered
            return probe.getsockname()[0]
    except OSError:
        return socket.gethostname()


def check_listen(host: str, port: int) -> None:
    """Refuse, with one line, an address the server could not listen on (a bad host, a port in use),
    before viser tries in a thread of its own."""
    try:
        family, kind, proto, _, address = socket.getaddrinfo(host, port, type=socket.SOCK_STREAM)[0]
        with socket.socket(family, kind, proto) as probe:
            probe.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
            probe.bind(address)
    except (OSError, OverflowError, UnicodeError) as e:
        raise InputError(f"cannot listen on {host}:{port}: {getattr(e, 'strerror', None) or e}") from None
