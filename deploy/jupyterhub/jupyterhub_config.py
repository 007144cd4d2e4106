# JupyterHub for a whole aerophoto class on one machine (see README, "For instructors" → "A whole class on
# JupyterHub").  Start it with `python deploy/jupyterhub/launch.py` (a local demonstration) or, on the course
# server, as root:  jupyterhub -f deploy/jupyterhub/jupyterhub_config.py  with the AEROPHOTO_HUB_* settings
# below in the environment.
#
# What it sets up:
#   * JupyterHub 6 from PyPI (requirements.txt beside this file) and its proxy, configurable-http-proxy from npm
#     (package.json / package-lock.json beside this file: `npm ci` here);
#   * an authenticator: a shared password for students and an admin password for the instructor (for a demo
#     and the tests) — switch to the university's login with AEROPHOTO_HUB_AUTH=lti13 or ldap (below);
#   * the spawner (aerophoto_hub.py): each user's server in bubblewrap as their own uid, with their own home,
#     the book's Python read-only, nbgrader's exchange shared, a private /tmp, a memory limit per process;
#   * roles: the instructors' group gets the formgrader and the course folder ~/course, and may see the class
#     and stop/start students' servers; students get nbgrader's Assignments list only (no authoring tools);
#   * culling: idle servers (jupyterhub-idle-culler, a hub service) and idle kernels (in every server).
#
# Settings (environment variables; defaults in brackets):
#   AEROPHOTO_HUB_STATE        the hub's own folder: database, cookie secret, uid table, homes, exchange
#                              [/srv/aerophoto-hub]
#   AEROPHOTO_HUB_HOMES        the users' homes [<state>/home];  AEROPHOTO_HUB_EXCHANGE  nbgrader's exchange
#                              [<state>/exchange]
#   AEROPHOTO_HUB_IP, _PORT    where the proxy listens [127.0.0.1, 8000];  AEROPHOTO_HUB_API_PORT  the hub's
#                              own port [8081];  AEROPHOTO_HUB_PROXY_API_PORT  the proxy's API [8001]
#   AEROPHOTO_HUB_ROSTER       CSV student_id,record_book: the students allowed in (hub names = student ids;
#                              the same file is the course's roster.csv, copied into ~/course on the
#                              instructor's first start)
#   AEROPHOTO_HUB_INSTRUCTORS  comma-separated hub names of the instructors [teacher]
#   AEROPHOTO_HUB_ADMINS       comma-separated hub admins (with shared-password the instructors are admins too)
#   AEROPHOTO_HUB_AUTH         shared-password | lti13 | ldap | pam [shared-password]
#   AEROPHOTO_HUB_STUDENT_PASSWORD (≥ 8 characters), AEROPHOTO_HUB_INSTRUCTOR_PASSWORD (≥ 32) for shared-password
#   AEROPHOTO_HUB_STUDENT_MEM [3G], AEROPHOTO_HUB_INSTRUCTOR_MEM [4G]   address space per process
#   AEROPHOTO_HUB_CULL_TIMEOUT [3600] s idle before a server is stopped;  AEROPHOTO_HUB_CULL_EVERY [300] s
#   AEROPHOTO_HUB_KERNEL_CULL [1200] s idle before a kernel is shut down (its tab closed)
#   AEROPHOTO_HUB_ACTIVITY_INTERVAL [300] s between the servers' activity reports to the hub
#   AEROPHOTO_HUB_START_TIMEOUT [120] s a server may take to start
#   AEROPHOTO_HUB_ADMIN_TOKEN  optional: an API token for a "course-admin" service (user list, servers)
#   AEROPHOTO_HUB_SINGLEUSER_ARGS  optional extra arguments for every user's server (tests)

import csv
import os
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

from aerophoto_hub import NAME_RE, UidTable, prepare_exchange  # noqa: E402

c = get_config()  # noqa: F821


def env(name, default=None):
    value = os.environ.get(f"AEROPHOTO_HUB_{name}")
    return default if value in (None, "") else value


STATE = Path(env("STATE", "/srv/aerophoto-hub")).resolve()
STATE.mkdir(parents=True, exist_ok=True)
HOMES = Path(env("HOMES", STATE / "home"))
EXCHANGE = Path(env("EXCHANGE", STATE / "exchange"))


def read_roster(path):
    if not path:
        return {}
    with open(path, newline="", encoding="utf-8-sig") as fh:
        return {row["student_id"].strip(): row["record_book"].strip() for row in csv.DictReader(fh)
                if row.get("student_id", "").strip()}


ROSTER_FILE = env("ROSTER")
STUDENTS = sorted(read_roster(ROSTER_FILE))
INSTRUCTORS = sorted({n.strip() for n in env("INSTRUCTORS", "teacher").split(",") if n.strip()})
for name in STUDENTS + INSTRUCTORS:
    if not NAME_RE.match(name):
        raise SystemExit(f"hub user name {name!r} is not valid: {NAME_RE.pattern}")

# --- the hub and its proxy ------------------------------------------------------------------------------
c.JupyterHub.ip = env("IP", "127.0.0.1")
c.JupyterHub.port = int(env("PORT", "8000"))
c.JupyterHub.hub_ip = "127.0.0.1"
c.JupyterHub.hub_port = int(env("API_PORT", "8081"))
c.JupyterHub.db_url = f"sqlite:///{STATE / 'jupyterhub.sqlite'}"
c.JupyterHub.cookie_secret_file = str(STATE / "jupyterhub_cookie_secret")
c.JupyterHub.pid_file = str(STATE / "jupyterhub.pid")
c.JupyterHub.cleanup_servers = True  # the servers die with the hub anyway (bubblewrap's --die-with-parent)
chp = HERE / "node_modules" / ".bin" / "configurable-http-proxy"
c.ConfigurableHTTPProxy.command = [str(chp) if chp.exists() else "configurable-http-proxy"]
c.ConfigurableHTTPProxy.pid_file = str(STATE / "jupyterhub-proxy.pid")
c.ConfigurableHTTPProxy.api_url = f"http://127.0.0.1:{int(env('PROXY_API_PORT', '8001'))}"
c.JupyterHub.last_activity_interval = int(env("ACTIVITY_INTERVAL", "300"))
# a start request answers at once (the browser shows the start's progress page): a class logging in together
# does not queue behind one another's 10 s waits
c.JupyterHub.tornado_settings = {"slow_spawn_timeout": 0}

# --- who may log in ----------------------------------------------------------------------------------------
auth = env("AUTH", "shared-password")
c.Authenticator.username_pattern = NAME_RE.pattern
c.Authenticator.admin_users = {n.strip() for n in env("ADMINS", "").split(",") if n.strip()}
if auth == "shared-password":
    # Built into JupyterHub (≥ 5.3): students share one password, the instructors (hub admins) use another of
    # ≥ 32 characters, so a student cannot log in as the instructor.  Any student can log in as any other
    # student, though: for a demonstration and the tests, never for a graded course.
    c.JupyterHub.authenticator_class = "shared-password"
    c.Authenticator.admin_users |= set(INSTRUCTORS)  # the admin password is the instructors' (hub admins here)
    c.SharedPasswordAuthenticator.user_password = env("STUDENT_PASSWORD")
    c.SharedPasswordAuthenticator.admin_password = env("INSTRUCTOR_PASSWORD")
    c.Authenticator.allowed_users = set(STUDENTS) | set(INSTRUCTORS)
elif auth == "lti13":
    # The LMS (Moodle, Canvas…) logs students in: pip install jupyterhub-ltiauthenticator, register the hub as an
    # LTI 1.3 tool in the LMS and fill in what it shows you.  Hub names are the LMS's user ids (add them to the
    # roster) — or its e-mail or login name through username_key.
    c.JupyterHub.authenticator_class = "ltiauthenticator.lti13.auth.LTI13Authenticator"
    c.LTI13Authenticator.issuer = env("LTI_ISSUER")
    c.LTI13Authenticator.client_id = [env("LTI_CLIENT_ID")]
    c.LTI13Authenticator.authorize_url = env("LTI_AUTHORIZE_URL")
    c.LTI13Authenticator.jwks_endpoint = env("LTI_JWKS_URL")
    c.LTI13Authenticator.username_key = env("LTI_USERNAME_KEY", "sub")
    c.Authenticator.allow_all = True  # whoever the LMS sends from the course
elif auth == "ldap":
    # The university's directory: pip install jupyterhub-ldapauthenticator.
    c.JupyterHub.authenticator_class = "ldapauthenticator.LDAPAuthenticator"
    c.LDAPAuthenticator.server_address = env("LDAP_SERVER")
    c.LDAPAuthenticator.bind_dn_template = [env("LDAP_BIND_DN_TEMPLATE", "uid={username},ou=people,dc=example,dc=org")]
    c.LDAPAuthenticator.use_ssl = True
    c.Authenticator.allowed_users = set(STUDENTS) | set(INSTRUCTORS)
elif auth == "pam":
    # System accounts of this machine (students created with useradd): their own uids and homes.
    c.JupyterHub.authenticator_class = "pam"
    c.AerophotoSpawner.system_users = True
    c.Authenticator.allowed_users = set(STUDENTS) | set(INSTRUCTORS)
else:
    raise SystemExit(f"AEROPHOTO_HUB_AUTH = {auth!r} is not valid; expected shared-password, lti13, ldap or pam")

c.JupyterHub.load_groups = {
    "instructors": {"users": INSTRUCTORS},
    "students": {"users": STUDENTS},
}
roles = [
    # the instructor sees the class and may stop or start a student's server — but not open it
    {"name": "instructor", "description": "the course's instructors: see the class, stop/start students' servers",
     "scopes": ["list:users", "read:users:activity", "read:servers!group=students", "admin:servers!group=students"],
     "groups": ["instructors"]},
    {"name": "idle-culler", "description": "stop idle servers",
     "scopes": ["list:users", "read:users:activity", "read:servers", "delete:servers"],
     "services": ["idle-culler"]},
]
services = [{
    "name": "idle-culler",
    "command": [sys.executable, "-m", "jupyterhub_idle_culler", f"--timeout={int(env('CULL_TIMEOUT', '3600'))}",
                f"--cull-every={int(env('CULL_EVERY', '300'))}", "--concurrency=5"],
}]
if env("ADMIN_TOKEN"):
    services.append({"name": "course-admin", "api_token": env("ADMIN_TOKEN")})
    roles.append({"name": "course-admin", "description": "the launcher's view: users, groups, servers",
                  "scopes": ["admin:users", "admin:groups", "admin:servers", "list:users", "read:users",
                             "read:servers", "read:users:activity"],
                  "services": ["course-admin"]})
c.JupyterHub.services = services
c.JupyterHub.load_roles = roles

# --- each user's server -------------------------------------------------------------------------------------
c.JupyterHub.spawner_class = "aerophoto_hub.AerophotoSpawner"
c.AerophotoSpawner.state_dir = str(STATE)
c.AerophotoSpawner.homes_dir = str(HOMES)
c.AerophotoSpawner.exchange_dir = str(EXCHANGE)
UID_BASE = 30000  # the users' uids: 30000, 30001, … in the order they are first seen (<state>/users.json)
c.AerophotoSpawner.uid_base = UID_BASE
c.Spawner.cmd = [str(Path(sys.executable).parent / "jupyterhub-singleuser")]
c.Spawner.default_url = "/lab"
# the limits are the package's (aerophoto.course.limits.HUB_STUDENT / HUB_INSTRUCTOR: 3 GB, 4 GB of address
# space per process); the environment may change the memory
if env("STUDENT_MEM"):
    c.Spawner.mem_limit = env("STUDENT_MEM")
if env("INSTRUCTOR_MEM"):
    c.AerophotoSpawner.instructor_mem_limit = env("INSTRUCTOR_MEM")
c.Spawner.start_timeout = int(env("START_TIMEOUT", "120"))  # a class logging in at once on a small machine
c.Spawner.http_timeout = int(env("START_TIMEOUT", "120"))
c.Spawner.environment = {"JUPYTERHUB_ACTIVITY_INTERVAL": env("ACTIVITY_INTERVAL", "300")}
kernel_cull = int(env("KERNEL_CULL", "1200"))
c.Spawner.args = [
    f"--MappingKernelManager.cull_idle_timeout={kernel_cull}",
    f"--MappingKernelManager.cull_interval={max(1, min(60, kernel_cull // 4))}",
    "--MappingKernelManager.cull_connected=False",   # a kernel with its tab open is kept
    f"--TerminalManager.cull_inactive_timeout={kernel_cull}",
    f"--TerminalManager.cull_interval={max(1, min(60, kernel_cull // 4))}",
    *[a for a in env("SINGLEUSER_ARGS", "").split() if a],
]


def pre_spawn(spawner):
    """The instructor's first start: the course folder ~/course with the hub's roster as its roster.csv."""
    if not spawner.is_instructor or not ROSTER_FILE or spawner.system_users:
        return
    uid, gid, home = spawner.account()
    spawner.prepare_home(uid, gid, home)
    course = home / "course"
    if not course.exists():
        course.mkdir(mode=0o700)
        os.chown(course, uid, gid)
    roster = course / "roster.csv"
    if not roster.exists():
        roster.write_bytes(Path(ROSTER_FILE).read_bytes())
        os.chown(roster, uid, gid)
        os.chmod(roster, 0o600)


c.Spawner.pre_spawn_hook = pre_spawn

# every user known now gets a uid, and the exchange its course folder owned by the (first) instructor
if auth != "pam":
    table = UidTable(STATE, UID_BASE)
    for name in INSTRUCTORS + STUDENTS:
        table.uid(name)
    table.write_etc()
    prepare_exchange(EXCHANGE, table.uid(INSTRUCTORS[0]) if INSTRUCTORS else None)
