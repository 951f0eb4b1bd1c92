// reference_agent.asl: bench/reference_agent.goal in AgentSpeak (python-agentspeak 0.2.2).
// One achievement of !run is one reasoning cycle of the GOAL agent: the event module's two
// forall rules, then the main module's four rules, each tried once. AgentSpeak has no
// declarative goals, so GOAL's goal checkpoint(N) is the belief checkpoint_goal(N) here.
// bench/cycles.py puts the belief limit(N) first: the agent stops after N cycles.

cycle(0).
sum(0).
flag(off).
reading(0, 3). reading(1, 7). reading(2, 1). reading(3, 9). reading(4, 4).
reading(5, 0). reading(6, 8). reading(7, 2). reading(8, 6). reading(9, 5).
weight(0, 2). weight(1, 3). weight(2, 5). weight(3, 7).
weight(4, 11). weight(5, 13). weight(6, 17).
checkpoint_goal(10).

toggle(on, off).
toggle(off, on).
threshold(C, T) :- T = C mod 10.
low(T, I) :- high(I) & reading(I, V) & V <= T.

!run.

+!run : cycle(C) & limit(L) & C < L <- !events; !main; !!run.
+!run <- true.

// event module: both forall rules.
+!events : cycle(C) & threshold(C, T)
    <- for (reading(I, V) & V > T & not high(I)) { +high(I); }
       .findall(I, low(T, I), Low);
       for (.member(I, Low)) { -high(I); }.

// main module, linearall: each rule tried once; the empty plans make a rule not applicable.
+!main <- !count; !accumulate; !flip; !checkpoint.

+!count : cycle(C) <- -cycle(C); +cycle(C + 1).
+!count <- true.

+!accumulate : cycle(C) & weight(C mod 7, W) & sum(S)
    <- -sum(S); +sum((S + W * C) mod 1000003).
+!accumulate <- true.

+!flip : flag(F) & toggle(F, G) <- -flag(F); +flag(G).
+!flip <- true.

+!checkpoint : checkpoint_goal(N) & not checkpoint(N) & cycle(C) & C >= N
    <- -checkpoint_goal(N); +checkpoint_goal(C + 10).
+!checkpoint <- true.
