// Placeholder until the pictures land.
