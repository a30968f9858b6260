// Placeholder replaced below once the capture readers land.
