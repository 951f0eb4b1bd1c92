/*  What confine.pl knows about SWI-Prolog's built-ins (included into ga_confine): which it
    refuses, sandbox or not, and how an agent's catch/3 and cleanup handlers are made to
    let the runtime's limits through.
*/

%   Built-ins no agent may call, sandbox or not: the other agents run in the same process.
process_wide(set_prolog_flag/2).
process_wide(create_prolog_flag/3).
process_wide(consult/1).
process_wide(load_files/1).
process_wide(load_files/2).             % its stream(S) option loads any text under any name
process_wide('[|]'/2).                  % [File, ...]: consult
process_wide(reexport/1).
process_wide(reexport/2).
process_wide(autoload/1).
process_wide(autoload/2).
process_wide(ensure_loaded/1).
process_wide(include/1).
process_wide(make/0).
process_wide(qcompile/1).
process_wide(qcompile/2).
process_wide(load_foreign_library/1).
process_wide(load_foreign_library/2).
process_wide(use_foreign_library/1).
process_wide(use_foreign_library/2).
process_wide(open_shared_object/2).
process_wide(open_shared_object/3).
process_wide(chdir/1).
process_wide(halt/0).
process_wide(halt/1).
process_wide(abort/0).
process_wide(thread_signal/2).
process_wide(set_prolog_stack/2).
process_wide(garbage_collect_atoms/0).
process_wide(thread_create/2).          % a thread runs outside the agent's limits, beside
process_wide(thread_create/3).          % the one thread the runtime drives Prolog from
process_wide(thread_create_in_pool/4).
process_wide(concurrent/3).
process_wide(concurrent_forall/2).
process_wide(concurrent_forall/3).
process_wide(concurrent_maplist/2).
process_wide(concurrent_maplist/3).
process_wide(concurrent_maplist/4).
process_wide(first_solution/3).
process_wide(call_in_thread/2).
process_wide(on_signal/3).              % the process's signal handlers (Ctrl-C, the watchdog's)
process_wide(format_predicate/2).       % a format directive for every format/2,3 call
process_wide(prolog_listen/2).          % called on events of every agent (their clauses)
process_wide(prolog_listen/3).
process_wide(prolog_unlisten/2).
process_wide(at_halt/1).                % runs when the process ends, outside every limit
process_wide(cancel_halt/1).
process_wide(alarm/3).                  % library(time): a goal run later, in whatever query
process_wide(alarm/4).                  % (another agent's) is running then
process_wide(alarm_at/3).
process_wide(alarm_at/4).
process_wide(remove_alarm/1).
process_wide(install_alarm/1).
process_wide(install_alarm/2).
process_wide(uninstall_alarm/1).
process_wide(set_prolog_IO/3).
process_wide(expects_dialect/1).       % the process's dialect flag and global operators

%   Attribute hooks run in the module an attribute is named after: put_attr(X, freeze, G)
%   would call any G, unchecked, when X is bound.
attribute_hook(put_attr/3).
attribute_hook(put_attrs/2).

%   Built-ins that enumerate modules or atoms, or reach into frames or the module system.
private(current_module/1).
private(module_property/2).
private(current_atom/1).
private(current_blob/2).
private(current_functor/2).
private(current_key/1).
private(current_flag/1).
private(prolog_current_frame/1).
private(prolog_frame_attribute/3).
private(prolog_choice_attribute/3).
private((@)/2).
private(set_module/1).
private(module/2).
private(add_import_module/3).
private(delete_import_module/2).
private(context_module/1).
private(strip_module/3).

%   Built-ins that print a message or term: a message format(F, Args) or a line F-Args
%   runs a goal for ~@ in F, and the write option portray_goal(G) calls G.
printing_goal(G) :-
    functor(G, Name, Arity),
    memberchk(Name/Arity, [print_message/2, print_message_lines/3, message_to_codes/3,
                           debug/3, write_term/2, write_term/3, print/2, write_length/3,
                           portray_clause/3, assertion_failed/2]).

sandbox_library(Name) :-
    memberchk(Name, [lists, apply, aggregate, pairs, assoc, ordsets, ugraphs, rbtrees, nb_set,
                     heaps, random, solution_sequences, yall, occurs, terms, sort, option,
                     error, gensym, varnumbers, when, dif, dicts, strings, tables,
                     'dcg/basics', 'dcg/high_order']).

%   Under the sandbox, library(sandbox) must find the call safe (its goal arguments,
%   checked here, replaced by a safe placeholder of the same arity). The library is loaded
%   when the first sandboxed agent is (load_sandbox/0): it loads library(apply_macros),
%   whose goal expansion then applies to every file compiled in the process (a run without
%   --sandbox must not change how Prolog compiles the user's own files).
sandbox_allows(_, c(_, false, _)) :- !.
sandbox_allows(G, _) :-
    own_introspection(G), !.
sandbox_allows(G, c(M, true, _)) :-
    placeholders(G, Probe),
    catch(sandbox:safe_goal(M:Probe), E, unsafe(E, G)).

%!  load_sandbox is det.
%   Loads library(sandbox) before the first sandboxed agent is read (load/5), not under an
%   agent's inference limit in the middle of a rule.
load_sandbox :-
    use_module(library(sandbox), []).

%   stoppable(+Goal0, +Ctx, -Goal): agent code never holds back what stops it. Its
%   catch/3 lets the runtime's exceptions pass (a limit, an abort: a catch-all whose
%   recovery runs the runaway goal again would run for ever), and its cleanup handlers run
%   as ordinary code (see cleanup_call/4).
stoppable(catch(G, C, R), c(M, _, _), catch(G, E, ga_confine:recover(E, C, M:R))) :- !.
stoppable(catch_with_backtrace(G, C, R), c(M, _, _),
          catch_with_backtrace(G, E, ga_confine:recover(E, C, M:R))) :- !.
stoppable(setup_call_cleanup(S, G, C), c(M, _, _),
          ga_confine:cleanup_call(M:S, M:G, _, M:C)) :- !.
stoppable(setup_call_catcher_cleanup(S, G, K, C), c(M, _, _),
          ga_confine:cleanup_call(M:S, M:G, K, M:C)) :- !.
stoppable(call_cleanup(G, C), c(M, _, _), ga_confine:cleanup_call(true, M:G, _, M:C)) :- !.
stoppable(G, _, G).

%!  recover(+Ball, ?Catcher, :Recovery) is nondet.
%   The recovery of an agent's catch/3: the runtime's exceptions pass on.
recover(Ball, Catcher, Recovery) :-
    (   runtime_ball(Ball)
    ->  throw(Ball)
    ;   Ball = Catcher
    ->  call(Recovery)
    ;   throw(Ball)
    ).

%!  agent_throw(+Ball) is det.
%   An agent's throw/1 of a ball only known at run time (see prepare/3).
agent_throw(Ball) :-
    (   runtime_ball(Ball)
    ->  refuse_ball(Ball)
    ;   throw(Ball)
    ).

refuse_ball(Ball) :-
    refuse("throw(~q): this exception is the runtime's (a limit, an abort), not an agent's",
           [Ball]).

runtime_ball(Ball) :-
    nonvar(Ball),
    (   Ball == '$aborted'
    ;   Ball = ga_limit(_)
    ;   Ball == '$ga_python'
    ;   Ball == inference_limit_exceeded
    ;   Ball = unwind(_)
    ),
    !.

%!  cleanup_call(:Setup, :Goal, ?Catcher, :Cleanup) is semidet.
%   An agent's setup_call_cleanup/3 (and setup_call_catcher_cleanup/4, call_cleanup/2):
%   Goal's first solution only, and Cleanup run as ordinary code after it. SWI-Prolog runs
%   cleanup handlers with signals held back, so neither the time limit nor an abort (nor
%   SIGTERM) could stop a runaway one; a limit or an abort that ends Goal skips Cleanup.
cleanup_call(Setup, Goal, Catcher, Cleanup) :-
    once(Setup),
    (   catch(Goal, Ball, true)
    ->  (   var(Ball) -> Outcome = exit ; Outcome = exception(Ball) )
    ;   Outcome = fail
    ),
    (   Outcome = exception(Stop), runtime_ball(Stop)
    ->  throw(Stop)
    ;   Catcher = Outcome
    ->  ignore(Cleanup)
    ;   true
    ),
    (   Outcome = exception(Error)
    ->  throw(Error)
    ;   Outcome == exit
    ).
