"""Layer 2, physics: one file per topic module (flight, quality, displacement, mosaic, triangulation, …)."""
