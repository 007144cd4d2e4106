"""Layer 4, the course's content: guide/ (printed tables and audits), labs/ and tasks/ (one file per chapter)."""
