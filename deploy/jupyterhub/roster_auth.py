"""The course hub's default log-in: a password of their own for every student and instructor, made from the roster.

    python deploy/jupyterhub/roster_auth.py --roster roster.csv --instructors teacher \
        --passwords /srv/aerophoto-hub/passwords.json --credentials credentials.csv

gives every name of the roster (and each instructor) that has no password yet a random one (16 characters for a
student, 32 for an instructor), stores only its scrypt hash in ``--passwords`` (mode 0600, read by the hub at
every log-in: a name added later works without a restart) and writes the new passwords in plain text, once, to
``--credentials`` (a CSV ``name,password`` for the instructor to hand out; mode 0600).  ``--reset NAME`` gives
one person a new password.  ``launch.py`` does the same for its demonstration hub.

:class:`RosterPasswordAuthenticator` is the JupyterHub authenticator reading that file
(``AEROPHOTO_HUB_AUTH=roster-passwords``, the default of ``jupyterhub_config.py``): a student's password opens
that student's account only.  Standard library and JupyterHub only; nothing is fetched from the network.
"""

from __future__ import annotations

import argparse
import base64
import csv
import hashlib
import hmac
import json
import os
import secrets
import tempfile
from pathlib import Path

_N, _R, _P = 2**14, 8, 1  # scrypt's cost: ~50 ms and 16 MB per check


def hash_password(password: str, *, salt: bytes | None = None) -> str:
    """``scrypt$N$r$p$salt$hash`` (base64) of ``password``."""
    salt = salt or secrets.token_bytes(16)
    digest = hashlib.scrypt(password.encode("utf-8"), salt=salt, n=_N, r=_R, p=_P, dklen=32)
    return "$".join(["scrypt", str(_N), str(_R), str(_P), base64.b64encode(salt).decode(),
                     base64.b64encode(digest).decode()])


def verify_password(password: str, stored: str) -> bool:
    """True when ``password`` matches ``stored`` (:func:`hash_password`'s form); never raises."""
    try:
        kind, n, r, p, salt, digest = str(stored).split("$")
        if kind != "scrypt":
            return False
        got = hashlib.scrypt(str(password).encode("utf-8"), salt=base64.b64decode(salt), n=int(n), r=int(r),
                             p=int(p), dklen=32)
        return hmac.compare_digest(got, base64.b64decode(digest))
    except (ValueError, TypeError):
        return False


def read_hashes(path) -> dict:
    try:
        data = json.loads(Path(path).read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return {}
    return {str(k): str(v) for k, v in data.items()} if isinstance(data, dict) else {}


def _write_private(path: Path, text: str) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", dir=path.parent)
    try:
        os.fchmod(fd, 0o600)
        with os.fdopen(fd, "w", encoding="utf-8") as fh:
            fh.write(text)
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise


def make_passwords(names, passwords_file, *, instructors=(), reset=()) -> dict:
    """New random passwords for the ``names`` (and ``instructors``) without one, or in ``reset``.

    Stores their hashes in ``passwords_file`` (keeping the others); returns ``{name: password}`` of the new ones —
    the only time they exist in plain text.
    """
    path = Path(passwords_file)
    hashes = read_hashes(path)
    new = {}
    for name in [*names, *instructors]:
        if name in hashes and name not in reset:
            continue
        pw = secrets.token_urlsafe(24 if name in instructors else 12)
        new[name] = pw
        hashes[name] = hash_password(pw)
    if new or not path.exists():
        _write_private(path, json.dumps(hashes, indent=1, sort_keys=True) + "\n")
    return new


def set_passwords(passwords_file, passwords: dict) -> None:
    """Store the hashes of given ``{name: password}`` (the launcher's demonstration hub)."""
    path = Path(passwords_file)
    hashes = read_hashes(path)
    hashes.update({n: hash_password(pw) for n, pw in passwords.items()})
    _write_private(path, json.dumps(hashes, indent=1, sort_keys=True) + "\n")


def _authenticator_class():
    from jupyterhub.auth import Authenticator
    from traitlets import Unicode

    class RosterPasswordAuthenticator(Authenticator):
        """Each user logs in with their own password (hashes in ``passwords_file``; see the module notes)."""

        passwords_file = Unicode("", config=True, help="JSON {name: scrypt hash} written by roster_auth.py")

        async def authenticate(self, handler, data):
            name = self.normalize_username(str((data or {}).get("username", "")))
            password = str((data or {}).get("password", ""))
            stored = read_hashes(self.passwords_file).get(name)
            if not stored or not password:
                return None
            import asyncio

            ok = await asyncio.get_running_loop().run_in_executor(None, verify_password, password, stored)
            return name if ok else None

    return RosterPasswordAuthenticator


def __getattr__(name: str):
    if name == "RosterPasswordAuthenticator":
        cls = _authenticator_class()
        globals()[name] = cls
        return cls
    raise AttributeError(name)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description="Per-user passwords for the aerophoto course hub, from the roster.")
    ap.add_argument("--roster", type=Path, required=True, help="CSV with a student_id column")
    ap.add_argument("--instructors", default="teacher", help="comma-separated instructor names [teacher]")
    ap.add_argument("--passwords", type=Path, required=True, help="the hashes file the hub reads (AEROPHOTO_HUB_PASSWORDS)")
    ap.add_argument("--credentials", type=Path, required=True, help="CSV name,password of the new passwords (0600)")
    ap.add_argument("--reset", action="append", default=[], help="give NAME a new password (repeatable)")
    args = ap.parse_args(argv)
    with open(args.roster, newline="", encoding="utf-8-sig") as fh:
        students = [r["student_id"].strip() for r in csv.DictReader(fh) if r.get("student_id", "").strip()]
    instructors = [n.strip() for n in args.instructors.split(",") if n.strip()]
    new = make_passwords(students, args.passwords, instructors=instructors, reset=args.reset)
    lines = ["name,password", *(f"{n},{pw}" for n, pw in sorted(new.items()))]
    _write_private(args.credentials, "\n".join(lines) + "\n")
    print(f"{len(new)} new password(s) in {args.credentials} (hand them out, then delete the file); "
          f"hashes in {args.passwords}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
