"""Layer 1, foundation: _validate, geometry, plane, variants (and every public function's bad-input refusal)."""
