% reference_floor.pl: the floor of bench/cycles.py. The decision logic of
% bench/reference_agent.goal hand-compiled into ONE predicate, ref_floor:step/0, called once
% per cycle from Python: the event module's two forall rules, the main module's four rules
% (linearall: each tried once, first answer), then blind commitment. Beliefs are dynamic
% facts; the goal base is goal/1.
:- module(ref_floor, [reset/0, step/0, state/5]).

:- dynamic cycle/1, sum/1, flag/1, reading/2, weight/2, high/1, checkpoint/1, goal/1.

toggle(on, off).
toggle(off, on).
threshold(Cycle, T) :- T is Cycle mod 10.

%!  reset is det.
%   Back to the agent's initial beliefs and goals.
reset :-
    retractall(cycle(_)), retractall(sum(_)), retractall(flag(_)),
    retractall(reading(_, _)), retractall(weight(_, _)), retractall(high(_)),
    retractall(checkpoint(_)), retractall(goal(_)),
    assertz(cycle(0)), assertz(sum(0)), assertz(flag(off)),
    forall(nth0(I, [3, 7, 1, 9, 4, 0, 8, 2, 6, 5], V), assertz(reading(I, V))),
    forall(nth0(K, [2, 3, 5, 7, 11, 13, 17], W), assertz(weight(K, W))),
    assertz(goal(checkpoint(10))).

%!  step is det.
%   One reasoning cycle of the reference agent.
step :-
    forall(( cycle(C), threshold(C, T), reading(I, V), V > T, \+ high(I) ),
           assertz(high(I))),
    forall(( cycle(C), threshold(C, T), high(I), reading(I, V), V =< T ),
           retract(high(I))),
    (   cycle(C1), Next is C1 + 1
    ->  retract(cycle(C1)), assertz(cycle(Next))
    ;   true
    ),
    (   cycle(C2), K is C2 mod 7, weight(K, W), sum(S), New is (S + W * C2) mod 1000003
    ->  retract(sum(S)), assertz(sum(New))
    ;   true
    ),
    (   flag(F), toggle(F, G)
    ->  retract(flag(F)), assertz(flag(G))
    ;   true
    ),
    (   goal(checkpoint(N)), \+ checkpoint(N), cycle(C3), C3 >= N, Later is C3 + 10
    ->  retract(goal(checkpoint(N))), assertz(goal(checkpoint(Later)))
    ;   true
    ),
    forall(( goal(Goal), call(Goal) ), retract(goal(Goal))).

%!  state(-Cycle, -Sum, -Flag, -Checkpoint, -High) is det.
%   The part of the mental state the benchmark compares across implementations.
state(Cycle, Sum, Flag, Checkpoint, High) :-
    cycle(Cycle), sum(Sum), flag(Flag), goal(checkpoint(Checkpoint)),
    findall(I, high(I), Unsorted), msort(Unsorted, High).
