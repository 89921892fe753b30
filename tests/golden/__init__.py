"""Golden-regression tier: small cases per model family and their stored outputs (README.md)."""
