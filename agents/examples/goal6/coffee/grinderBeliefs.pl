have(beans).
canMake(grinder, [grounds]).
