// SPDX-License-Identifier: Apache-2.0
// svpwm_mmio: svpwm_core behind a bus-agnostic register port -- svpwm_regs (generated from rdl/svpwm.rdl,
// map in docs/registers.md) + svpwm_core. The bus wrappers (svpwm_axil, svpwm_wb) put their protocol
// adapter in front of it. Every RW register field drives the core input of the same name; the core
// samples its inputs at its sample points, so a write takes effect at an update point, never in the
// middle of a carrier period.
// Parameters:
//   AddrWidth - byte address width of the register port (>= 8); addresses without a register read 0
//   AddrEarly - svpwm_regs AddrEarly: 1 when addr_i already holds the request's address in the clock
//               before every request (uart_reg_bridge): the register select is then decoded a clock
//               ahead, registered (shorter paths); 0 (default) for the bus adapters
//   MinPeriod, FreqMax, GatePol - passed to svpwm_core (GatePol is also the reset value of CTRL.pol);
//               MinPeriod defaults to the core's default of the build (svpwm_pkg::min_period(Features))
//   ClkHz     - the core clock in Hz, read back in CLK_HZ for host software (0 = not stated; >= 0)
//   Features  - the build: a mask of svpwm_pkg::Feat* bits (svpwm_pkg::CfgFull default, CfgFoc, CfgVf,
//               CfgMinimal, CfgTiny; model/svpwm_model/config.py), svpwm_core's and svpwm_regs': the
//               registers and fields of a feature not built read 0 and ignore writes (docs/registers.md,
//               column features); read back in FEATURES.features
//   Trim      - 1: the iCEstick's board cut of svpwm_regs (docs/registers.md, column trim): no MP (the
//               core runs with a minimum pulse of 0, every gate pulse still lasts >= DT), no CTRL.mode
//               (mode 0, FREQ) and CTRL.adc_trig, no CARRIER, PERIOD_ACT, CMP_A..C; read back in FEATURES.trim
//   CntWidth  - the core's carrier / period / compare width, 12..16 (default 16, the PERIOD field's; the
//               iCEstick uses 12 to fit the HX1K); a PERIOD above 2^CntWidth - 1 runs as 2^CntWidth - 1
//               and sets STATUS.period_clamp while it is there; likewise an ADC_PT0 / ADC_PT1 count above
//               2^CntWidth - 1 reaches the core as 2^CntWidth - 1 (beyond P: the peak) and a WIN_MIN above
//               2^(CntWidth+1) - 1 as 2^(CntWidth+1) - 1 (no window that long). Read back in CONFIG.cnt_width.
//   The other widths are those of the register map: PhaseWidth 34, FreqWidth 24, DtWidth 10 (CONFIG).
// Latency: register port: a write is in the register the clock after req_i; read data the clock after.
// Restrictions: see svpwm_regs (one access per clock, be_i byte lanes; AddrEarly = 1: addr_i unchanged
//   from the clock before a request).
`default_nettype none

module svpwm_mmio #(
  parameter logic [31:0] Features = svpwm_pkg::CfgFull,
  parameter bit         Trim      = 1'b0,
  parameter int         AddrWidth = 8,
  parameter bit         AddrEarly = 1'b0,
  parameter int         MinPeriod = svpwm_pkg::min_period(Features),
  parameter int         FreqMax   = (1 << 23) - 1,
  parameter logic [1:0] GatePol   = 2'b00,
  parameter int         ClkHz     = 0,
  parameter int         CntWidth  = 16
) (
  input  logic                 clk_i,              // core and bus clock
  input  logic                 rst_ni,             // asynchronous reset, active low
  // register port (from svpwm_axil_if / svpwm_wb_if)
  input  logic                 req_i,
  input  logic                 we_i,
  input  logic [AddrWidth-1:0] addr_i,
  input  logic [31:0]          wdata_i,
  input  logic [3:0]           be_i,
  output logic [31:0]          rdata_o,
  // inverter side
  input  logic                 fault_i,            // trip input, asynchronous, active high
  input  logic                 sync_i,             // another core's sync_o (same clock), CTRL.sync_en
  output logic [2:0]           gate_hi_o,          // {c, b, a} high-side gate pins (polarity applied)
  output logic [2:0]           gate_lo_o,          // {c, b, a} low-side gate pins (polarity applied)
  output logic [2:0]           pole_o,             // {c, b, a} modulator states before dead time
  output logic                 valley_o,           // pulse: first clock of a carrier period
  output logic                 peak_o,             // pulse: carrier peak
  output logic                 update_o,           // pulse: new compare values active from this clock
  output logic                 adc_trig_o,         // pulse: ADC trigger (CTRL.adc_trig, ADC_PT0 / ADC_PT1)
  output logic [1:0]           adc_pt_o,           // pulse: ADC trigger point k (ADC_PT0 / ADC_PT1; feature adc)
  output logic                 sync_o,             // pulse at each valley, for other cores' sync_i
  output logic                 running_o,          // gates modulating (e.g. an LED)
  output logic                 tripped_o           // safe state forced (e.g. an LED)
);

  // Field widths of the register map (rdl/svpwm.rdl) = the core's width parameters (CntWidth: up to)
  localparam int PeriodBits = 16;
  localparam int WinBits    = PeriodBits + 1;   // WIN_MIN, WIN_LO_*, WIN_HI_*: CntWidth + 1 of a 16-bit core
  localparam int PhaseWidth = 34;
  localparam int FreqWidth  = 24;
  localparam int DtWidth    = 10;

  // the core needs DtWidth + 2 <= CntWidth
  if (CntWidth < DtWidth + 2 || CntWidth > PeriodBits) begin : gen_bad_cnt_width
`ifdef __ICARUS__  // Icarus 11 has no elaboration-time tasks: at time 0
    initial $fatal(1, "svpwm_mmio: CntWidth must be %0d..%0d, got %0d (%m)", DtWidth + 2,
                   PeriodBits, CntWidth);
`else              // at elaboration (Yosys formats $display only, then stops at $error)
    initial $display("svpwm_mmio: CntWidth must be %0d..%0d, got %0d (%m)", DtWidth + 2,
                     PeriodBits, CntWidth);
    $error("svpwm_mmio: CntWidth must be %0d..%0d, got %0d", DtWidth + 2, PeriodBits, CntWidth);
`endif
  end

  // ---- register block <-> core -------------------------------------------------------------------
  logic                        en, sync_en, trip_cbc, safe_lo, lock, fault_clear, dtc_en, om, vsc_off;
  logic [2:0]                  isign;
  logic [1:0]                  pol, upd, dpwm, adc_trig;
  logic [2:0]                  mode;
  logic [FreqWidth-1:0]        freq;
  logic [15:0]                 m, theta, v1, v2, vf_boost, vf_slope, vf_mmax;
  logic [PeriodBits-1:0]       period;
  logic [CntWidth-1:0]         period_core, carrier, period_act;
  logic                        period_over, period_clamp_core;
  logic [DtWidth-1:0]          dt, dtf, mp;
  logic                        dtf_en;
  logic [7:0]                  presc;
  logic                        carrier_up, sat, cfg_err, period_clamp, freq_clamp, fault, locked;
  logic [2:0]                  sector;
  logic [3*CntWidth-1:0]       cmp;
  // current sampling (feature adc): the trigger points and the minimum window as the register map has
  // them (16-bit counts, a 17-bit window), the core's ports (CntWidth), the shunt-window report
  logic [1:0]                  pt_en, pt_dn;
  logic [PeriodBits-1:0]       pt_cnt0, pt_cnt1;
  logic [WinBits-1:0]          win_min;
  logic [2*CntWidth-1:0]       pt_cnt_core;
  logic [CntWidth:0]           win_min_core;
  logic [3*(CntWidth+1)-1:0]   win_lo, win_hi;
  logic [2:0]                  win_ok;
  logic [1:0]                  win_recon;

  svpwm_regs #(
    .AddrWidth (AddrWidth),
    .AddrEarly (AddrEarly),
    .DtWidth   (8'(DtWidth)),
    .CntWidth  (8'(CntWidth)),
    .FreqWidth (8'(FreqWidth)),
    .PhaseWidth(8'(PhaseWidth)),
    .GatePol   (GatePol),
    .ClkHz     (ClkHz),
    .Features  (Features),
    .Trim      (Trim)
  ) u_regs (
    .clk_i (clk_i), .rst_ni (rst_ni),
    .req_i (req_i), .we_i (we_i), .addr_i (addr_i), .wdata_i (wdata_i), .be_i (be_i), .rdata_o (rdata_o),
    .ctrl_en_o (en), .ctrl_sync_en_o (sync_en), .ctrl_trip_cbc_o (trip_cbc), .ctrl_safe_lo_o (safe_lo),
    .ctrl_pol_o (pol), .ctrl_lock_o (lock), .ctrl_fault_clear_o (fault_clear), .ctrl_mode_o (mode),
    .ctrl_upd_o (upd), .ctrl_dpwm_o (dpwm), .ctrl_om_o (om), .ctrl_vsc_off_o (vsc_off), .ctrl_adc_trig_o (adc_trig),
    .freq_o (freq), .m_o (m), .theta_o (theta), .v1_o (v1), .v2_o (v2),
    .vf_boost_o (vf_boost), .vf_slope_o (vf_slope), .vf_mmax_o (vf_mmax),
    .period_o (period), .dt_dt_o (dt), .dt_dtf_o (dtf), .dt_dtf_en_o (dtf_en), .mp_o (mp),
    .presc_o (presc), .dtc_en_o (dtc_en), .dtc_isign_o (isign),
    .adc_pt0_cnt_o (pt_cnt0), .adc_pt0_dn_o (pt_dn[0]), .adc_pt0_en_o (pt_en[0]),
    .adc_pt1_cnt_o (pt_cnt1), .adc_pt1_dn_o (pt_dn[1]), .adc_pt1_en_o (pt_en[1]), .win_min_o (win_min),
    .status_running_i (running_o), .status_sat_i (sat), .status_cfg_err_i (cfg_err),
    .status_period_clamp_i (period_clamp), .status_freq_clamp_i (freq_clamp), .status_fault_i (fault),
    .status_tripped_i (tripped_o), .status_locked_i (locked), .status_sector_i (sector),
    .carrier_count_i (PeriodBits'(carrier)), .carrier_up_i (carrier_up),
    .period_act_i (PeriodBits'(period_act)),
    .cmp_a_i (PeriodBits'(cmp[CntWidth-1:0])), .cmp_b_i (PeriodBits'(cmp[2*CntWidth-1:CntWidth])),
    .cmp_c_i (PeriodBits'(cmp[3*CntWidth-1:2*CntWidth])),
    .win_lo_a_i (WinBits'(win_lo[0 +: CntWidth+1])),
    .win_lo_b_i (WinBits'(win_lo[CntWidth+1 +: CntWidth+1])),
    .win_lo_c_i (WinBits'(win_lo[2*(CntWidth+1) +: CntWidth+1])),
    .win_hi_a_i (WinBits'(win_hi[0 +: CntWidth+1])),
    .win_hi_b_i (WinBits'(win_hi[CntWidth+1 +: CntWidth+1])),
    .win_hi_c_i (WinBits'(win_hi[2*(CntWidth+1) +: CntWidth+1])),
    .win_status_ok_i (win_ok), .win_status_recon_i (win_recon)
  );

  // PERIOD above the core's range: the largest period it has (a clamp, flagged like a raised period);
  // the trigger-point counts and the minimum window likewise (a count beyond any P fires at the peak,
  // a minimum beyond any window marks none readable: what the register's value means on a 16-bit core)
  if (CntWidth < PeriodBits) begin : gen_period_clamp
    assign period_over  = |period[PeriodBits-1:CntWidth];
    assign period_core  = period_over ? '1 : period[CntWidth-1:0];
    assign pt_cnt_core  = {(|pt_cnt1[PeriodBits-1:CntWidth]) ? {CntWidth{1'b1}} : pt_cnt1[CntWidth-1:0],
                           (|pt_cnt0[PeriodBits-1:CntWidth]) ? {CntWidth{1'b1}} : pt_cnt0[CntWidth-1:0]};
    assign win_min_core = (|win_min[WinBits-1:CntWidth+1]) ? '1 : win_min[CntWidth:0];
  end else begin : gen_period_full
    assign period_over  = 1'b0;
    assign period_core  = period;
    assign pt_cnt_core  = {pt_cnt1, pt_cnt0};
    assign win_min_core = win_min;
  end
  assign period_clamp = period_clamp_core || period_over;

  svpwm_core #(
    .CntWidth (CntWidth), .PhaseWidth (PhaseWidth), .FreqWidth (FreqWidth), .DtWidth (DtWidth),
    .MinPeriod (MinPeriod), .FreqMax (FreqMax), .GatePol (GatePol),
    .Features (Features)
  ) u_core (
    .clk_i (clk_i), .rst_ni (rst_ni), .en_i (en), .mode_i (mode), .freq_i (freq), .m_i (m),
    .theta_i (theta), .v1_i (v1), .v2_i (v2), .vf_boost_i (vf_boost), .vf_slope_i (vf_slope),
    .vf_mmax_i (vf_mmax), .dpwm_i (dpwm), .om_i (om), .vsc_en_i (!vsc_off), .upd_i (upd), .presc_i (presc),
    .period_i (period_core), .dt_i (dt), .dtf_i (dtf), .dtf_en_i (dtf_en), .mp_i (mp), .dtc_en_i (dtc_en),
    .adc_pt_en_i (pt_en), .adc_pt_dn_i (pt_dn), .adc_pt_cnt_i (pt_cnt_core), .win_min_i (win_min_core),
    .isign_i (isign), .adc_trig_i (adc_trig), .sync_en_i (sync_en), .sync_i (sync_i),
    .fault_i (fault_i), .fault_clear_i (fault_clear), .trip_cbc_i (trip_cbc), .safe_lo_i (safe_lo),
    .pol_i (pol), .lock_i (lock),
    .gate_hi_o (gate_hi_o), .gate_lo_o (gate_lo_o), .pole_o (pole_o), .carrier_o (carrier),
    .carrier_up_o (carrier_up), .valley_o (valley_o), .peak_o (peak_o), .update_o (update_o),
    .adc_pt_o (adc_pt_o), .win_lo_o (win_lo), .win_hi_o (win_hi), .win_ok_o (win_ok),
    .win_recon_o (win_recon),
    .adc_trig_o (adc_trig_o), .sync_o (sync_o), .sector_o (sector), .cmp_o (cmp),
    .period_o (period_act), .running_o (running_o), .sat_o (sat), .cfg_err_o (cfg_err),
    .period_clamp_o (period_clamp_core), .freq_clamp_o (freq_clamp), .fault_o (fault),
    .tripped_o (tripped_o), .locked_o (locked)
  );

endmodule

`default_nettype wire
