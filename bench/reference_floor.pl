% reference_floor.pl: the floor of bench/cycles.py. The decision logic of
% bench/reference_agent.goal hand-compiled into ONE predicate, ref_floor:step/0, called once
% per cycle from Python: the event module's two forall rules, the main module's four rules
% (linearall: each tried once, first answer), then blind commitment. Beliefs are dynamic
% facts; the goal base is goal/1. Each rule is its own predicate too (see step/0).
:- module(ref_floor, [reset/0, step/0, state/5, event_high/0, event_low/0, count/0,
                      accumulate/0, flip/0, move_checkpoint/0, commit/0]).

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
    event_high, event_low, count, accumulate, flip, move_checkpoint, commit.

%   The rules one by one (bench/cycles.py also calls them one Prolog call each, to show what
%   a runtime that compiles each rule, actions included, into one clause could reach).
%   Event module (forall rules).
event_high :-
    forall(( cycle(C), threshold(C, T), reading(I, V), V > T, \+ high(I) ),
           assertz(high(I))).
event_low :-
    forall(( cycle(C), threshold(C, T), high(I), reading(I, V), V =< T ),
           retract(high(I))).

%   Main module (linearall: each rule tried once, first answer).
count :-
    (   cycle(C), Next is C + 1
    ->  retract(cycle(C)), assertz(cycle(Next))
    ;   true
    ).
accumulate :-
    (   cycle(C), K is C mod 7, weight(K, W), sum(S), New is (S + W * C) mod 1000003
    ->  retract(sum(S)), assertz(sum(New))
    ;   true
    ).
flip :-
    (   flag(F), toggle(F, G)
    ->  retract(flag(F)), assertz(flag(G))
    ;   true
    ).
move_checkpoint :-
    (   goal(checkpoint(N)), \+ checkpoint(N), cycle(C), C >= N, Later is C + 10
    ->  retract(goal(checkpoint(N))), assertz(goal(checkpoint(Later)))
    ;   true
    ).

%   Blind commitment: goals whose facts are all believed are dropped.
commit :-
    forall(( goal(Goal), call(Goal) ), retract(goal(Goal))).

%!  state(-Cycle, -Sum, -Flag, -Checkpoint, -High) is det.
%   The part of the mental state the benchmark compares across implementations.
state(Cycle, Sum, Flag, Checkpoint, High) :-
    cycle(Cycle), sum(Sum), flag(Flag), goal(checkpoint(Checkpoint)),
    findall(I, high(I), Unsorted), msort(Unsorted, High).
