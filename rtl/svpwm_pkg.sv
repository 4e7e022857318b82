// SPDX-License-Identifier: Apache-2.0
// svpwm_pkg: the latencies and shared constants of the core, derived in one place.
// svpwm_calc's latency is set by its program; the sample lead (clocks from an input sample to its update
// point) and the default MinPeriod follow from it. The model mirrors these (model/svpwm_model).
// Parameters: none. Latency: n/a. Restrictions: read it before the files that import it.
package svpwm_pkg;

  // clocks from svpwm_calc start_i to done_o (full core: every mode; compact core: FREQ only)
  localparam int CalcLatencyFull    = 38;
  localparam int CalcLatencyCompact = 225;
  // smallest MinPeriod default of the full core (the shortest half period the tests exercise)
  localparam int MinPeriodBase      = 48;

  function automatic int calc_latency(input bit compact);
    calc_latency = compact ? CalcLatencyCompact : CalcLatencyFull;
  endfunction

  // clocks from an input sample to the update point: the computation + 1 load clock
  function automatic int sample_lead(input bit compact);
    sample_lead = calc_latency(compact) + 1;
  endfunction

  // default (and lowest legal) MinPeriod: the lead + 4 (the sample strobes' pipeline), at least MinPeriodBase
  function automatic int min_period_floor(input bit compact);
    min_period_floor = sample_lead(compact) + 4;
  endfunction

  function automatic int min_period(input bit compact);
    min_period = (min_period_floor(compact) > MinPeriodBase) ? min_period_floor(compact) : MinPeriodBase;
  endfunction

endpackage
