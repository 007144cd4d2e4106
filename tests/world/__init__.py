"""Layer 3, the virtual world: terrain, site, simulate, render."""
