have(coffee).
