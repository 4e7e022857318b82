// SPDX-License-Identifier: Apache-2.0
// reset_sync: reset synchroniser -- asynchronous assert, synchronous release.
// rst_no goes low at once when arst_ni goes low and rises Stages clocks after arst_ni has risen,
// on a clock edge, so every flop released by it sees a clean recovery time.
`default_nettype none

module reset_sync #(
  parameter int Stages = 2   // >= 2
) (
  input  wire  clk_i,
  input  wire  arst_ni,      // asynchronous reset request, active low
  output logic rst_no        // synchronised reset, active low
);
  logic [Stages-1:0] sync_q;

  always_ff @(posedge clk_i or negedge arst_ni) begin
    if (!arst_ni) sync_q <= '0;
    else          sync_q <= {sync_q[Stages-2:0], 1'b1};
  end

  assign rst_no = sync_q[Stages-1];
endmodule

`default_nettype wire
