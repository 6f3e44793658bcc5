// The paper's Example 1 style data: a plateau and a jump, where natural
// splines overshoot.
export const data = [[0, 1], [1, 1.5], [2, 1.2], [3, 6], [4, 9], [5, 9.2], [6, 9], [7, 3], [8, 2.5], [9, 2.8], [10, 2.6]];
