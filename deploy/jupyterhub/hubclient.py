"""A small client of the course hub, as one user: log in, start the server, files, nbgrader's Assignments, kernels.

Used by tests/course/test_hub.py and benchmarks/bench_hub.py (and usable from a script): everything goes through
the hub's proxy as a browser would — the login form, the hub's REST API with the user's own token, the
user's Jupyter server (contents API, nbgrader's ``/assignments`` handlers, kernels over the websocket).
"""

from __future__ import annotations

import asyncio
import json
import time
import uuid

import requests

COURSE_ID = "aerophoto"


class HubUserError(RuntimeError):
    pass


class HubUser:
    """One hub user: ``login()`` with the log-in form, then a token of their own for everything else."""

    def __init__(self, hub_url: str, name: str, password: str):
        self.hub_url = hub_url.rstrip("/")
        self.name = name
        self.password = password
        self.http = requests.Session()
        self.token: str | None = None

    # the hub ------------------------------------------------------------------------------------
    def login(self) -> HubUser:
        """Log in with the form (as a browser does), then make an API token of this user's own."""
        r = self.http.get(f"{self.hub_url}/hub/login", timeout=60)
        r.raise_for_status()
        xsrf = self.http.cookies.get("_xsrf", "")
        r = self.http.post(f"{self.hub_url}/hub/login?next=", data={"username": self.name, "password": self.password,
                                                                     "_xsrf": xsrf}, allow_redirects=False, timeout=60)
        if r.status_code != 302:
            raise HubUserError(f"{self.name}: log-in refused ({r.status_code})")
        r = self.http.post(f"{self.hub_url}/hub/api/users/{self.name}/tokens", json={"note": "hubclient"},
                           headers={"X-XSRFToken": self.http.cookies.get("_xsrf", xsrf)}, timeout=60)
        if r.status_code not in (200, 201):
            raise HubUserError(f"{self.name}: no token ({r.status_code} {r.text[:200]})")
        self.token = r.json()["token"]
        return self

    @property
    def headers(self) -> dict:
        return {"Authorization": f"token {self.token}"}

    def hub(self, method: str, path: str, body=None, ok=(200, 201, 202, 204)):
        r = requests.request(method, f"{self.hub_url}/hub/api{path}", json=body, headers=self.headers, timeout=120)
        if r.status_code not in ok:
            raise HubUserError(f"{self.name}: {method} /hub/api{path}: {r.status_code} {r.text[:300]}")
        return r.json() if r.content else {}

    def request_server(self) -> None:
        """Ask the hub to start this user's server (returns while it may still be starting)."""
        self.hub("POST", f"/users/{self.name}/server", ok=(201, 202, 400))

    def server_ready(self) -> bool:
        s = self.hub("GET", f"/users/{self.name}").get("servers", {}).get("")
        return bool(s and s.get("ready"))

    def start_server(self, timeout: float = 180) -> float:
        """Start (or find running) this user's server; returns the seconds until it answered.

        A server that is being stopped (e.g. by the idle culler) is waited for and started again."""
        t0 = time.perf_counter()
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            u = self.hub("GET", f"/users/{self.name}")
            s = u.get("servers", {}).get("")
            if s and s.get("ready"):
                return time.perf_counter() - t0
            if not s and not u.get("pending"):
                self.request_server()
            time.sleep(0.2)
        raise HubUserError(f"{self.name}'s server did not start within {timeout} s")

    # the user's server --------------------------------------------------------------------------
    @property
    def base(self) -> str:
        return f"{self.hub_url}/user/{self.name}"

    def get(self, path: str, **kw):
        return requests.get(f"{self.base}{path}", headers=self.headers, timeout=120, **kw)

    def post(self, path: str, **kw):
        return requests.post(f"{self.base}{path}", headers=self.headers, timeout=300, **kw)

    def read(self, path: str) -> dict:
        r = self.get(f"/api/contents/{path}", params={"content": 1})
        if r.status_code != 200:
            raise HubUserError(f"{self.name}: GET contents {path}: {r.status_code} {r.text[:200]}")
        return r.json()

    def listing(self, path: str = "") -> list[str]:
        return sorted(x["name"] for x in self.read(path)["content"])

    def write_notebook(self, path: str, nb: dict) -> None:
        r = requests.put(f"{self.base}/api/contents/{path}", headers=self.headers, timeout=120,
                         json={"type": "notebook", "format": "json", "content": nb})
        if r.status_code not in (200, 201):
            raise HubUserError(f"{self.name}: PUT contents {path}: {r.status_code} {r.text[:200]}")

    def assignments(self, action: str | None = None, assignment: str | None = None) -> list[dict]:
        """nbgrader's Assignments list (``action`` None) or one of its buttons: fetch, submit, fetch_feedback."""
        if action is None:
            r = self.get("/assignments", params={"course_id": COURSE_ID})
        else:
            r = self.post(f"/assignments/{action}", json={"course_id": COURSE_ID, "assignment_id": assignment})
        if r.status_code != 200:
            raise HubUserError(f"{self.name}: assignments {action}: {r.status_code} {r.text[:300]}")
        data = r.json()
        if not data.get("success", True):
            raise HubUserError(f"{self.name}: assignments {action}: {data.get('value')}")
        return data.get("value", data)

    # kernels ------------------------------------------------------------------------------------
    def start_kernel(self) -> str:
        r = self.post("/api/kernels", json={"name": "python3"})
        if r.status_code != 201:
            raise HubUserError(f"{self.name}: no kernel ({r.status_code} {r.text[:200]})")
        return r.json()["id"]

    def kernels(self) -> list[str]:
        r = self.get("/api/kernels")
        r.raise_for_status()
        return [k["id"] for k in r.json()]

    def shutdown_kernel(self, kid: str) -> None:
        requests.delete(f"{self.base}/api/kernels/{kid}", headers=self.headers, timeout=60)

    def run(self, code: str, *, kernel: str | None = None, timeout: float = 600) -> dict:
        """Run ``code`` in a kernel of this user's server (a new one, shut down after, unless ``kernel``).

        Returns ``{"stdout", "stderr", "error", "result", "seconds"}``.
        """
        own = kernel is None
        kid = kernel or self.start_kernel()
        try:
            return run_sync(self._run(kid, code, timeout))
        finally:
            if own:
                self.shutdown_kernel(kid)

    def ws_url(self, kid: str) -> str:
        return self.base.replace("http://", "ws://").replace("https://", "wss://") + f"/api/kernels/{kid}/channels"

    async def connect(self, kid: str):
        from tornado.httpclient import HTTPRequest
        from tornado.websocket import websocket_connect

        return await websocket_connect(HTTPRequest(self.ws_url(kid), headers=self.headers),
                                       max_message_size=64 * 1024 * 1024)

    async def _run(self, kid: str, code: str, timeout: float) -> dict:
        ws = await self.connect(kid)
        try:
            msg_id = send(ws, "execute_request", {"code": code, "silent": False, "store_history": False,
                                                  "user_expressions": {}, "allow_stdin": False,
                                                  "stop_on_error": True})
            out = {"stdout": "", "stderr": "", "error": None, "result": None}
            t0 = time.perf_counter()
            while True:
                msg = await asyncio.wait_for(recv(ws), timeout)
                if msg is None:
                    raise HubUserError(f"{self.name}: the kernel's websocket closed")
                if msg.get("parent_header", {}).get("msg_id") != msg_id or msg.get("channel") != "iopub":
                    continue
                kind, content = msg["header"]["msg_type"], msg["content"]
                if kind == "stream":
                    out[content["name"]] += content["text"]
                elif kind == "error":
                    out["error"] = f"{content['ename']}: {content['evalue']}"
                elif kind == "execute_result":
                    out["result"] = content["data"].get("text/plain")
                elif kind == "status" and content["execution_state"] == "idle":
                    out["seconds"] = time.perf_counter() - t0
                    return out
        finally:
            ws.close()


def run_sync(coro):
    """Run a coroutine to its end — in a thread of its own when this thread already runs an event loop
    (Playwright's sync API does)."""
    try:
        asyncio.get_running_loop()
    except RuntimeError:
        return asyncio.run(coro)
    from concurrent.futures import ThreadPoolExecutor

    with ThreadPoolExecutor(1) as pool:
        return pool.submit(asyncio.run, coro).result()


def message(msg_type: str, content: dict, channel: str = "shell") -> dict:
    mid = uuid.uuid4().hex
    return {"header": {"msg_id": mid, "msg_type": msg_type, "username": "", "session": uuid.uuid4().hex,
                       "date": "", "version": "5.3"},
            "parent_header": {}, "metadata": {}, "content": content, "channel": channel, "buffers": []}


def send(ws, msg_type: str, content: dict, channel: str = "shell") -> str:
    msg = message(msg_type, content, channel)
    ws.write_message(json.dumps(msg))
    return msg["header"]["msg_id"]


async def recv(ws):
    """The next JSON message from a kernel websocket (binary frames — widget buffers — are skipped)."""
    while True:
        raw = await ws.read_message()
        if raw is None:
            return None
        if isinstance(raw, bytes):
            continue
        return json.loads(raw)
