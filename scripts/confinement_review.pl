/*  What confine.pl does with each built-in an agent may write (scripts/confinement_review.py):
    the goal Name(_, ..., _) (a key predicate with the key k) prepared as agent text is
    loaded, without and with the sandbox.
*/
:- module(ga_review, [verdict/5, current_predicate_or_library/2]).

%!  verdict(+B, +Name, +Arity, -Plain, -Sandbox) is det.
%   Plain, Sandbox: refused(Why), checked (some goal is checked when it runs), sized
%   (what it makes is bounded before it starts: goalagent/kb/sizes.pl), agent (made the
%   agent's own: its key, its catch or cleanup), or allowed (as written).
verdict(B, Name, Arity, Plain, Sandbox) :-
    functor(G, Name, Arity),
    (   catch(ga_confine:key_family(Name/Arity, _), _, fail) -> arg(1, G, k) ; true ),
    mode_verdict(G, c(B, false, []), Plain),
    mode_verdict(G, c(B, true, []), Sandbox).

mode_verdict(G, Ctx, Verdict) :-
    catch(( ga_confine:prepare(G, Ctx, Out),
            (   Out == G
            ->  Verdict = allowed
            ;   sub_term(X, Out), compound(X), X = ga_confine:Checked, compound(Checked),
                functor(Checked, Name, _),
                memberchk(Name, [call_checked, closure_checked, grammar_checked])
            ->  Verdict = checked
            ;   sub_term(X, Out), compound(X), X = ga_sizes:_
            ->  Verdict = sized
            ;   Verdict = agent
            ) ),
          E,
          (   E = ga_refused(Why) -> Verdict = refused(Why) ; Verdict = refused(E) )).

%!  current_predicate_or_library(+Name, +Arity) is semidet.
%   SWI-Prolog 9.0.4 here has it, built in or in a library it autoloads.
current_predicate_or_library(Name, Arity) :-
    functor(Head, Name, Arity),
    (   predicate_property(system:Head, defined)
    ->  true
    ;   '$find_library'(_, Name, Arity, _, _)
    ).
