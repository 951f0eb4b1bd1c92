% Towers of Hanoi: discs numbered from 1, a higher number being a smaller disc; on(D, Pin,
% Below) are the percepts kept as beliefs.
:- dynamic on/3.
disc(D) :- on(D, _, _).
top_disc(D) :- findall(X, disc(X), Ds), max_list(Ds, D).
pin_of(D, P) :- on(D, P, _).
other(A, B, C) :- member(C, [0, 1, 2]), C \= A, C \= B.

% settle(D, T, M): M is the next move that gets discs D, D+1, ... (disc D and all smaller
% ones) onto pin T; fails when they are all there already.
settle(D, _, _) :- top_disc(N), D > N, !, fail.
settle(D, T, M) :- pin_of(D, T), !, D1 is D + 1, settle(D1, T, M).
settle(D, T, M) :- pin_of(D, P), other(P, T, O), D1 is D + 1,
    ( settle(D1, O, M) -> true ; M = move(D, T) ).

next_move(D, T) :- settle(1, 2, move(D, T)).
solved :- disc(_), \+ (disc(D), \+ pin_of(D, 2)).
