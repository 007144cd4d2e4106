"""Real-browser tests (Playwright + Debian chromium): run alone with ``pytest -m browser``."""
