have(water).
canMake(maker, [coffee]).
