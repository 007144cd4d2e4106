"""The course hub's default log-in: a password of each user's own, made from the roster (issue: grading holes, 9).

JupyterHub's shared-password log-in let any student log in as any other; the default is now
``roster-passwords`` (deploy/jupyterhub/roster_auth.py): each name of the roster and each instructor gets a random
password, only its scrypt hash is stored, and a password opens its own account only.  The shared password is
left behind an explicit ``AEROPHOTO_HUB_AUTH=shared-password`` (``launch.py --shared-password``).
"""

from __future__ import annotations

import asyncio
import csv
import json
import os
import stat
import sys

import pytest

from conftest import ROOT

HUB = ROOT / "deploy" / "jupyterhub"
sys.path.insert(0, str(HUB))

import roster_auth  # noqa: E402


IN_CI = os.environ.get("AEROPHOTO_CI") == "1"


def _auth(path):
    # JupyterHub comes from deploy/jupyterhub/requirements.txt, not environment.txt: this test is marked ``hub``
    # and runs in CI's second step, which installs it; in CI its absence is a failure, never a skip
    try:
        import jupyterhub  # noqa: F401
    except ImportError as e:
        if IN_CI:
            pytest.fail(f"the log-in test needs JupyterHub in CI: {e}; .ci/run installs "
                        "deploy/jupyterhub/requirements.txt", pytrace=False)
        pytest.skip("the log-in test needs JupyterHub: python -m pip install -r deploy/jupyterhub/requirements.txt")
    a = roster_auth.RosterPasswordAuthenticator(passwords_file=str(path))
    return lambda name, pw: asyncio.run(a.authenticate(None, {"username": name, "password": pw}))


@pytest.mark.hub
def test_each_student_logs_in_with_their_own_password_only(tmp_path):
    roster = tmp_path / "roster.csv"
    roster.write_text("student_id,record_book\npetrov,19-0457\nsidorova,19-0499\n", encoding="utf-8")
    hashes, creds = tmp_path / "state" / "passwords.json", tmp_path / "credentials.csv"
    assert roster_auth.main(["--roster", str(roster), "--instructors", "teacher", "--passwords", str(hashes),
                             "--credentials", str(creds)]) == 0
    pw = {r["name"]: r["password"] for r in csv.DictReader(open(creds, encoding="utf-8"))}
    assert sorted(pw) == ["petrov", "sidorova", "teacher"]
    assert len(set(pw.values())) == 3 and min(map(len, pw.values())) >= 16 and len(pw["teacher"]) >= 32
    for p in (hashes, creds):
        assert stat.S_IMODE(os.stat(p).st_mode) == 0o600
    stored = json.loads(hashes.read_text(encoding="utf-8"))
    assert all(v.startswith("scrypt$") and pw[k] not in v for k, v in stored.items())  # no password in clear
    login = _auth(hashes)
    assert login("petrov", pw["petrov"]) == "petrov"
    assert login("sidorova", pw["petrov"]) is None      # another student's password opens nothing
    assert login("teacher", pw["petrov"]) is None
    assert login("petrov", "") is None and login("nobody", pw["petrov"]) is None
    # a second run keeps everyone's password and makes one for a new name only; --reset gives a new one
    roster.write_text("student_id,record_book\npetrov,19-0457\nsidorova,19-0499\nivanova,19-0401\n",
                      encoding="utf-8")
    assert roster_auth.main(["--roster", str(roster), "--passwords", str(hashes), "--credentials", str(creds),
                             "--reset", "sidorova"]) == 0
    new = {r["name"]: r["password"] for r in csv.DictReader(open(creds, encoding="utf-8"))}
    assert sorted(new) == ["ivanova", "sidorova"] and new["sidorova"] != pw["sidorova"]
    assert login("petrov", pw["petrov"]) == "petrov" and login("sidorova", pw["sidorova"]) is None
    assert login("ivanova", new["ivanova"]) == "ivanova"


def test_the_hub_config_defaults_to_per_user_passwords():
    text = (HUB / "jupyterhub_config.py").read_text(encoding="utf-8")
    assert 'auth = env("AUTH", "roster-passwords")' in text
    launch = (HUB / "launch.py").read_text(encoding="utf-8")
    assert '"AEROPHOTO_HUB_AUTH": "shared-password"' in launch and "if self.shared_password:" in launch
