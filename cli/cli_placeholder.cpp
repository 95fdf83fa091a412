// Replaced by the command implementation.
