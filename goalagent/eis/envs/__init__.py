"""Small pure-Python environments with the vocabularies of GOAL's classic example agents."""
