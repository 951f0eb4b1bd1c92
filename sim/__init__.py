"""The MuJoCo world of garbage cans: scenes, the world wrapper and its EIS environments."""
