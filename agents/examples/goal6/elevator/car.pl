% An elevator car: where to go next, and when all riders are served. The percepts sent
% every cycle (eButtonOn/1, fButtonOn/2, carPosition/1) and on change (doorState/1,
% people/1) are kept as beliefs, as are the calls other cars claimed (claimed/2).
:- dynamic eButtonOn/1, fButtonOn/2, carPosition/1, claimed/2, calls_seen/0.
distance(F, D) :- carPosition(P), D is abs(F - P).
open_call(F, Dir) :- fButtonOn(F, Dir), \+ claimed(F, Dir).

% next_stop(F, Dir): where to go, and the direction to light on arrival.
next_stop(F, Dir) :-
    findall(D-G, (eButtonOn(G), distance(G, D)), Requests), Requests \= [], !,
    keysort(Requests, [_-F|_]), light_after(F, Dir).
next_stop(F, Dir) :-
    findall(D-(G/Di), (open_call(G, Di), distance(G, D)), Calls), Calls \= [],
    keysort(Calls, [_-(F/Dir)|_]).
light_after(F, up) :- eButtonOn(G), G > F, !.
light_after(F, down) :- eButtonOn(G), G < F, !.
light_after(F, Dir) :- fButtonOn(F, Dir), !.
light_after(_, up).

served :- calls_seen, \+ fButtonOn(_, _), \+ eButtonOn(_), people(0), doorState(closed).
