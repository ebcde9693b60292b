# The `granular` executable (owned by the flow work).
