// Smoke-test harness for the cocotb/simulator infrastructure.
// A free-running counter clocked by a clock generated in SystemVerilog
// (`always #5`, i.e. 100 MHz), so no cocotb Clock coroutine is needed.
`timescale 1ns/1ps
`default_nettype none

module tb_smoke #(
    parameter int WIDTH     = 32,
    parameter int TICK_LOG2 = 4      // `tick` is high once every 2**TICK_LOG2 cycles
) (
    input  wire logic             rst_n,  // driven by cocotb
    output      logic [WIDTH-1:0] count,
    output      logic             tick
);
    logic clk;
    initial clk = 1'b0;
    always #5 clk = ~clk;

    always_ff @(posedge clk or negedge rst_n) begin
        if (!rst_n) count <= '0;
        else        count <= count + 1'b1;
    end

    // High while the low TICK_LOG2 bits of count are all ones, so its rising
    // edges happen when count == k * 2**TICK_LOG2 - 1.
    assign tick = &count[TICK_LOG2-1:0];
endmodule

`default_nettype wire
