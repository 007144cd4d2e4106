"""What an open chapter costs while nobody moves: one student's kernel and server, idle (issue 32).

The hub benchmark (bench_hub.py) counts the CPU of a whole class sitting idle; this one isolates one student:
a ``jupyter_server`` on a free loopback port with one kernel, a websocket client connected to it as an open tab
is (no page: nothing answers the widgets), chapter 00's own setup cell and footprint demo executed through it —
then the kernel's and the server's CPU (user + system, psutil) over :data:`IDLE_S` s of nothing, and the messages
the client received meanwhile.  Also the same with a bare kernel (``x = 1``) beside it, in the same run.

Prints nothing (benchmarks/run.py prints the JSON).
"""

from __future__ import annotations

import asyncio
import json
import os
import signal
import socket
import subprocess
import sys
import tempfile
import time
import uuid

from _timing import chapter_opening, hubclient

#: seconds of nothing over which the CPU is measured
IDLE_S = 30.0
#: the kernel's first cells' own work may still be finishing (a deferred table): waited out before measuring
SETTLE_S = 3.0


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


async def _one(code: str, idle_s: float) -> dict:
    import psutil
    from tornado.httpclient import AsyncHTTPClient, HTTPRequest
    from tornado.websocket import websocket_connect

    port, token = _free_port(), uuid.uuid4().hex
    root = tempfile.mkdtemp(prefix="aerophoto-idle-")
    srv = subprocess.Popen([sys.executable, "-m", "jupyter_server", f"--port={port}", "--no-browser",
                            f"--IdentityProvider.token={token}", f"--ServerApp.root_dir={root}", "--allow-root",
                            "--ServerApp.open_browser=False"],
                           stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                           env={**os.environ, "AEROPHOTO_HOME": root})
    try:
        http, base = AsyncHTTPClient(), f"http://127.0.0.1:{port}"
        for _ in range(600):
            try:
                await http.fetch(f"{base}/api/status?token={token}")
                break
            except Exception:  # noqa: BLE001 - not up yet
                await asyncio.sleep(0.2)
        r = await http.fetch(HTTPRequest(f"{base}/api/kernels?token={token}", method="POST", body="{}"))
        kid = json.loads(r.body)["id"]
        ws = await websocket_connect(f"ws://127.0.0.1:{port}/api/kernels/{kid}/channels?token={token}")
        hc = hubclient()  # the kernel protocol's message, as the hub tests send it
        msg_id = hc.send(ws, "execute_request", {"code": code, "silent": False, "store_history": True,
                                                 "user_expressions": {}, "allow_stdin": False})
        state = {"counting": False, "done": False, "error": None, "seen": {}}

        async def reader():
            while (m := await ws.read_message()) is not None:
                j = None if isinstance(m, bytes) else json.loads(m)
                kind = "binary frame" if j is None else j["header"]["msg_type"]
                if state["counting"]:
                    state["seen"][kind] = state["seen"].get(kind, 0) + 1
                if kind == "error":
                    state["error"] = j["content"].get("ename")
                elif kind == "execute_reply" and j["parent_header"].get("msg_id") == msg_id:
                    state["done"] = True

        task = asyncio.ensure_future(reader())
        t_open = time.perf_counter()
        while not state["done"]:
            if time.perf_counter() - t_open > 300:
                raise RuntimeError("the chapter's first cells did not finish in 300 s")
            await asyncio.sleep(0.05)
        if state["error"]:
            raise RuntimeError(f"the chapter's first cells failed: {state['error']}")
        open_s = time.perf_counter() - t_open
        await asyncio.sleep(SETTLE_S)
        server = psutil.Process(srv.pid)
        kernel = next(p for p in server.children(recursive=True) if "ipykernel" in " ".join(p.cmdline()))

        def cpu(p):
            t = p.cpu_times()
            return t.user + t.system

        k0, s0, t0 = cpu(kernel), cpu(server), time.perf_counter()
        state["counting"] = True
        await asyncio.sleep(idle_s)
        dt = time.perf_counter() - t0
        k1, s1 = cpu(kernel), cpu(server)
        task.cancel()
        ws.close()
        return {"open_s": round(open_s, 2), "idle_s": round(dt, 1),
                "kernel_core_share": round((k1 - k0) / dt, 5), "server_core_share": round((s1 - s0) / dt, 5),
                "kernel_threads": kernel.num_threads(), "messages_while_idle": state["seen"]}
    finally:
        srv.send_signal(signal.SIGINT)
        try:
            srv.wait(10)
        except subprocess.TimeoutExpired:
            srv.kill()


def run(quick: bool = False) -> dict:
    idle = 10.0 if quick else IDLE_S
    out = {"idle_s": idle, "load_before": round(os.getloadavg()[0], 2)}
    out["bare kernel (x = 1)"] = asyncio.run(_one("x = 1", idle))
    out["chapter 00 open (setup + footprint demo)"] = asyncio.run(_one(chapter_opening("00_start_here", "demo-footprint"), idle))
    out["load_after"] = round(os.getloadavg()[0], 2)
    return out
