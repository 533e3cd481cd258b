"""What the reports measure: each pair's ink against the keys' blend."""
